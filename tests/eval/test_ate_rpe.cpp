// ATE, RPE and association with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/eval/evaluate.hpp"

namespace twinslam::eval {
namespace {

const RpeSegment& segment(const EvalResult& r, const std::string& key) {
  for (const auto& s : r.rpe) {
    if (s.key == key) return s;
  }
  throw std::runtime_error("no RPE segment " + key);
}

TEST(Ate, GaussianNoiseGivesExpectedRmseAndMean) {
  // Isotropic position noise sigma per axis: |e| follows a Maxwell distribution with RMSE sigma*sqrt(3) and mean
  // 2*sigma*sqrt(2/pi). Rotation noise sigma_r per tangent axis: RMSE of the angle = sigma_r*sqrt(3).
  const double sigma_m = 0.05, sigma_rad = 0.002;
  const Trajectory gt = test::helix(40000, 10'000'000);
  Trajectory est = gt;
  std::mt19937 rng(42);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (auto& pose : est.poses) {
    pose.T_XB.translation() += sigma_m * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    const Eigen::Vector3d w = sigma_rad * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    pose.T_XB.linear() = pose.T_XB.linear() * Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  }
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_EQ(r.n, 40000u);
  EXPECT_NEAR(r.ate.pos.rmse, sigma_m * std::sqrt(3.0), 0.02 * sigma_m * std::sqrt(3.0));
  EXPECT_NEAR(r.ate.pos.mean, 2.0 * sigma_m * std::sqrt(2.0 / M_PI), 0.02 * sigma_m);
  const double rot_rmse_deg = sigma_rad * std::sqrt(3.0) * 180.0 / M_PI;
  EXPECT_NEAR(r.ate.rot.rmse, rot_rmse_deg, 0.02 * rot_rmse_deg);
}

TEST(Ate, ConstantOffsetGivesExactStatistics) {
  const Trajectory gt = test::helix(1000);
  Trajectory est = gt;
  for (auto& pose : est.poses) pose.T_XB.translation() += Eigen::Vector3d(0.3, 0.0, -0.4);  // |offset| = 0.5 m
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_NEAR(r.ate.pos.rmse, 0.5, 1e-12);
  EXPECT_NEAR(r.ate.pos.mean, 0.5, 1e-12);
  EXPECT_NEAR(r.ate.pos.median, 0.5, 1e-12);
  EXPECT_NEAR(r.ate.pos.std, 0.0, 1e-9);
  EXPECT_NEAR(r.ate.pos.max, 0.5, 1e-12);
  EXPECT_NEAR(r.ate.rot.max, 0.0, 1e-9);
}

TEST(Association, FiveMillisecondOffsetStillAssociatesEveryPose) {
  const Trajectory gt = test::helix(2000, 50'000'000);
  Trajectory est = gt;
  for (auto& pose : est.poses) pose.stamp_ns += 5'000'000;
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_EQ(r.n, gt.size());
  EXPECT_LT(r.ate.pos.max, 1e-12);  // paired with its own pose, not a neighbour 50 ms away
}

TEST(Association, EachGroundTruthPoseIsUsedOnce) {
  // Both estimate poses are closest to the ground-truth pose at 0 ms; it goes to the closer one (1 ms).
  Trajectory gt, est;
  gt.poses = {make_pose(0, {0, 0, 0}, Eigen::Quaterniond::Identity()),
              make_pose(100'000'000, {1, 0, 0}, Eigen::Quaterniond::Identity())};
  est.poses = {make_pose(1'000'000, {0, 0, 0}, Eigen::Quaterniond::Identity()),
               make_pose(3'000'000, {0, 0, 0}, Eigen::Quaterniond::Identity())};
  const auto m = associate(gt, est);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].gt, 0u);
  EXPECT_EQ(m[0].est, 0u);
}

TEST(Association, StampsFurtherThanTheWindowDoNotAssociate) {
  const Trajectory gt = test::helix(100, 100'000'000);
  Trajectory est = gt;
  for (auto& pose : est.poses) pose.stamp_ns += 30'000'000;  // 30 ms from one pose, 70 ms from the next
  EXPECT_TRUE(associate(gt, est).empty());
  EXPECT_EQ(associate(gt, est, 40'000'000).size(), 100u);
}

TEST(Association, NoOverlapIsAnInputErrorNamingBothFiles) {
  Trajectory gt = test::helix(100, 50'000'000, 0);
  Trajectory est = test::helix(100, 50'000'000, 60'000'000'000);  // starts a minute after the ground truth ends
  gt.source = "gt.tum";
  est.source = "est.tum";
  try {
    evaluate(gt, est, {});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no estimate pose within 20 ms"), std::string::npos) << what;
    EXPECT_NE(what.find("gt.tum"), std::string::npos) << what;
    EXPECT_NE(what.find("est.tum"), std::string::npos) << what;
  }
}

TEST(Evaluate, EmptyTrajectoryIsAnInputError) {
  Trajectory empty;
  empty.source = "empty.tum";
  EXPECT_THROW(evaluate(test::helix(10), empty, {}), InputError);
  EXPECT_THROW(evaluate(empty, test::helix(10), {}), InputError);
}

TEST(Rpe, ConstantScaleDriftGivesItsPercentage) {
  // Straight 300 m path; the estimate travels 1 % too far (p_est = 1.01 p_gt): every segment is 1 % too long.
  const Trajectory gt = test::straight_line(6001, 1.0);  // 0.05 m spacing
  Trajectory est = gt;
  for (auto& pose : est.poses) pose.T_XB.translation() *= 1.01;
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_NEAR(r.length_m, 300.0, 1e-9);
  for (const char* key : {"10m", "50m", "100m", "10%", "50%"}) {
    const RpeSegment& s = segment(r, key);
    ASSERT_GT(s.trans_pct_stats.n, 0u) << key;
    EXPECT_NEAR(s.trans_pct_stats.mean, 1.0, 1e-9) << key;
    EXPECT_NEAR(s.trans_pct_stats.max, 1.0, 1e-9) << key;
    EXPECT_NEAR(s.rot_deg_per_m_stats.max, 0.0, 1e-9) << key;
  }
  EXPECT_EQ(segment(r, "50%").length_m, 150.0);
  // The same drift is a pure scale to sim3 alignment.
  EvalConfig sim3;
  sim3.align = AlignMode::Sim3;
  EXPECT_LT(segment(evaluate(gt, est, sim3), "50m").trans_pct_stats.max, 1e-9);
}

TEST(Rpe, ConstantHeadingDriftGivesItsRatePerMetre) {
  // Straight path, the estimate's heading drifts 0.02 deg per metre travelled: relative rotation error 0.02 deg/m.
  const double rate_deg_per_m = 0.02;
  const Trajectory gt = test::straight_line(4001, 1.0);
  Trajectory est = gt;
  for (auto& pose : est.poses) {
    const double s_m = pose.T_XB.translation().x();
    pose.T_XB.linear() = Eigen::AngleAxisd(rate_deg_per_m * s_m * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_NEAR(segment(r, "10m").rot_deg_per_m_stats.mean, rate_deg_per_m, 1e-9);
  EXPECT_NEAR(segment(r, "100m").rot_deg_per_m_stats.max, rate_deg_per_m, 1e-9);
}

TEST(Rpe, SegmentsLongerThanTheTrajectoryAreEmpty) {
  const EvalResult r = evaluate(test::straight_line(401, 1.0), test::straight_line(401, 1.0), {});  // 20 m
  EXPECT_GT(segment(r, "10m").trans_pct_stats.n, 0u);
  EXPECT_EQ(segment(r, "50m").trans_pct_stats.n, 0u);
  EXPECT_EQ(segment(r, "100m").trans_pct_stats.n, 0u);
}

TEST(Stats, KnownList) {
  const ErrorStats s = compute_stats({4.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
}

}  // namespace
}  // namespace twinslam::eval
