// The loosely coupled GNSS + VIO pose graph (vio-gnss-loose): it must pull a drifting VIO back to W with GNSS, leave
// a perfect VIO where it is when the GNSS is unbiased, resist a gross outlier, and keep the VIO's roll and pitch.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/loose_gnss_fusion.hpp"

namespace twinslam::estimator {
namespace {

constexpr std::int64_t kFrameNs = 50'000'000;  // VIO at 20 Hz
constexpr int kFramesPerFix = 4;               // GNSS at 5 Hz

// The true body pose at frame k: a 40 m circle at 2 m/s, heading along the path, 10 m up.
Eigen::Isometry3d truth(int k) {
  const double t = k * 0.05, w = 2.0 / 40.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(40 * std::cos(w * t), 40 * std::sin(w * t), 10);
  T.linear() = Eigen::AngleAxisd(w * t + M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

// A VIO in its own frame L whose heading drifts `deg_per_min` (yaw drift makes the position error grow with the path).
Eigen::Isometry3d vio(int k, const Eigen::Isometry3d& T_LW, double deg_per_min) {
  const double yaw = deg_per_min * (k * 0.05 / 60.0) * M_PI / 180.0;
  const Eigen::Isometry3d T_WB = truth(k);
  Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();
  drift.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  drift.translation() = truth(0).translation() - drift.linear() * truth(0).translation();  // turns about the start
  return T_LW * drift * T_WB;
}

struct Flight {
  double final_error_m = 0;     // fused position error at the end
  double vio_error_m = 0;       // the VIO with the start alignment only, at the end
  Eigen::Isometry3d T_WB_final;
  LooseGnssFusionCounts counts;
};

Flight fly(int frames, double deg_per_min, double gnss_sigma_m, int outlier_fix = -1) {
  Eigen::Isometry3d T_LW = Eigen::Isometry3d::Identity();
  T_LW.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_LW.translation() = Eigen::Vector3d(5, -3, 1);
  LooseGnssFusion fusion;
  fusion.start(T_LW.inverse());  // the alignment found at the start (exact here)
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, gnss_sigma_m);
  const Eigen::Matrix3d cov = gnss_sigma_m * gnss_sigma_m * Eigen::Matrix3d::Identity();
  for (int k = 0; k < frames; ++k) {
    if (k > 0 && k % kFramesPerFix == 0) {
      // The fix is half a frame before this frame's VIO pose: paired by interpolation.
      const std::int64_t stamp = k * kFrameNs - kFrameNs / 2;
      Eigen::Vector3d z = 0.5 * (truth(k - 1).translation() + truth(k).translation());
      z += Eigen::Vector3d(n(rng), n(rng), n(rng));
      if (k / kFramesPerFix == outlier_fix) z += Eigen::Vector3d(80, -60, 0);
      fusion.add_fix(stamp, z, cov);
    }
    fusion.add_odometry(k * kFrameNs, vio(k, T_LW, deg_per_min));
  }
  Flight r;
  const Eigen::Isometry3d T_LB = vio(frames - 1, T_LW, deg_per_min);
  r.T_WB_final = fusion.T_WL() * T_LB;
  r.final_error_m = (r.T_WB_final.translation() - truth(frames - 1).translation()).norm();
  r.vio_error_m = ((T_LW.inverse() * T_LB).translation() - truth(frames - 1).translation()).norm();
  r.counts = fusion.counts();
  return r;
}

TEST(LooseGnssFusion, PullsADriftingVioBackToTheWorld) {
  // 3 minutes, 3 deg/min of heading drift (0.025 deg/m, a poor real VIO): the VIO alone ends metres away.
  const Flight r = fly(3600, 3.0, 1.0);
  EXPECT_GT(r.vio_error_m, 5.0);
  EXPECT_LT(r.final_error_m, 1.5) << "vio alone " << r.vio_error_m << " m";
  EXPECT_GT(r.counts.fixes_used, 800u);
  EXPECT_EQ(r.counts.fixes_unpaired, 0u);
}

TEST(LooseGnssFusion, LeavesAPerfectVioWhereItIs) {
  const Flight r = fly(2400, 0.0, 2.0);
  EXPECT_LT(r.final_error_m, 0.8);
}

TEST(LooseGnssFusion, AGrossOutlierMovesTheEstimateLittle) {
  const Flight clean = fly(1200, 0.0, 1.0);
  const Flight with_outlier = fly(1200, 0.0, 1.0, 200);  // 100 m off, 20 s before the end
  EXPECT_LT((with_outlier.T_WB_final.translation() - clean.T_WB_final.translation()).norm(), 0.5);
}

TEST(LooseGnssFusion, KeepsTheVioRollAndPitch) {
  const Flight r = fly(2400, 3.0, 3.0);
  // Truth and VIO are level: the fused body z axis must stay up.
  const Eigen::Vector3d z_W = r.T_WB_final.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(z_W.z(), std::cos(0.5 * M_PI / 180.0));
}

TEST(LooseGnssFusion, IgnoresFixesBeforeTheStartAndUnusableOnes) {
  LooseGnssFusion fusion;
  fusion.add_fix(1, Eigen::Vector3d(100, 0, 0), Eigen::Matrix3d::Identity());
  fusion.add_odometry(2, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(fusion.started());
  EXPECT_TRUE(fusion.T_WL().isApprox(Eigen::Isometry3d::Identity()));
  fusion.start(Eigen::Isometry3d::Identity());
  fusion.add_odometry(kFrameNs, Eigen::Isometry3d::Identity());
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity();
  bad(0, 0) = std::nan("");
  fusion.add_fix(kFrameNs + 1, Eigen::Vector3d(1, 0, 0), bad);
  fusion.add_fix(kFrameNs + 2, Eigen::Vector3d(1, 0, 0), -Eigen::Matrix3d::Identity());
  fusion.add_odometry(2 * kFrameNs, Eigen::Isometry3d::Identity());
  EXPECT_EQ(fusion.counts().fixes_unpaired, 2u);
  EXPECT_EQ(fusion.counts().fixes_used, 0u);
  EXPECT_TRUE(fusion.T_WL().isApprox(Eigen::Isometry3d::Identity()));
}

TEST(LooseGnssFusion, ConfigErrorsNameTheField) {
  LooseGnssFusionConfig c;
  c.window_nodes = 1;
  try {
    c.validate();
    FAIL() << "accepted window_nodes 1";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("window_nodes"), std::string::npos);
  }
  c = {};
  c.odometry_sigma_per_m = std::nan("");
  EXPECT_THROW(c.validate(), InputError);
}

}  // namespace
}  // namespace twinslam::estimator
