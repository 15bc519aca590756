// The LocalMap's landmarks (issue 12): the window's plus those that left it within the time and distance horizon.
#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/landmark_horizon.hpp"

namespace twinslam::estimator {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

LandmarkEstimate at(std::int64_t id, double x) { return {id, Eigen::Vector3d(x, 0, 0), 0.8}; }

std::vector<std::int64_t> ids(const std::vector<LandmarkEstimate>& v) {
  std::vector<std::int64_t> out;
  for (const auto& l : v) out.push_back(l.id);
  return out;
}

TEST(LandmarkHorizon, KeepsLandmarksThatLeftTheWindowWithinTheTimeHorizonWithTheirLastEstimate) {
  LandmarkHorizon h({.horizon_s = 2.0, .horizon_m = 100.0, .max_landmarks = 100});
  EXPECT_EQ(ids(h.update(0, Eigen::Vector3d::Zero(), {at(1, 1.0), at(2, 2.0)})), (std::vector<std::int64_t>{1, 2}));
  // Landmark 1 leaves the window; 2 stays with a new estimate; 3 is new.
  const auto second = h.update(1 * kSecond, Eigen::Vector3d::Zero(), {at(2, 2.5), at(3, 3.0)});
  ASSERT_EQ(ids(second), (std::vector<std::int64_t>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(second[0].p_L.x(), 1.0);  // its last estimate
  EXPECT_DOUBLE_EQ(second[1].p_L.x(), 2.5);  // the window's current one
  // 2.5 s after landmark 1 was last seen: gone; 2 and 3 were seen 1.5 s ago.
  EXPECT_EQ(ids(h.update(2500 * kSecond / 1000, Eigen::Vector3d::Zero(), {})), (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(h.remembered(), 2u);
}

TEST(LandmarkHorizon, KeepsTheEstimateFromWhenALandmarkWasBestObserved) {
  LandmarkHorizon h({.horizon_s = 10.0, .horizon_m = 100.0, .max_landmarks = 100});
  h.update(0, Eigen::Vector3d::Zero(), {{1, Eigen::Vector3d(1, 0, 0), 0.4}});
  h.update(kSecond, Eigen::Vector3d::Zero(), {{1, Eigen::Vector3d(2, 0, 0), 0.9}});
  // While in the window: its current estimate, however poor.
  const auto in_window = h.update(2 * kSecond, Eigen::Vector3d::Zero(), {{1, Eigen::Vector3d(3, 0, 0), 0.25}});
  ASSERT_EQ(in_window.size(), 1u);
  EXPECT_DOUBLE_EQ(in_window[0].p_L.x(), 3.0);
  const auto out = h.update(3 * kSecond, Eigen::Vector3d::Zero(), {});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].p_L.x(), 2.0);
  EXPECT_DOUBLE_EQ(out[0].quality, 0.9);
  // The time horizon counts from the last keyframe that had it in the window (2 s), not from its best.
  EXPECT_EQ(h.update(11 * kSecond, Eigen::Vector3d::Zero(), {}).size(), 1u);
  EXPECT_EQ(h.update(12500 * kSecond / 1000, Eigen::Vector3d::Zero(), {}).size(), 0u);
}

TEST(LandmarkHorizon, DropsRememberedLandmarksFarFromTheKeyframeButNeverTheWindowsOwn) {
  LandmarkHorizon h({.horizon_s = 10.0, .horizon_m = 5.0, .max_landmarks = 100});
  h.update(0, Eigen::Vector3d::Zero(), {at(1, 1.0), at(2, 20.0)});
  // The body moved to x = 18: landmark 1 (17 m away) is out, 2 (2 m) stays, and 4 is in the window though 30 m away.
  EXPECT_EQ(ids(h.update(kSecond, Eigen::Vector3d(18, 0, 0), {at(4, 48.0)})), (std::vector<std::int64_t>{2, 4}));
  // Back near the start: landmark 1 is still remembered (within the time horizon) and comes back.
  EXPECT_EQ(ids(h.update(2 * kSecond, Eigen::Vector3d::Zero(), {})), (std::vector<std::int64_t>{1}));
}

TEST(LandmarkHorizon, ZeroHorizonIsTheWindowAloneAndTheCapKeepsTheMostRecent) {
  LandmarkHorizon window_only({.horizon_s = 0.0, .horizon_m = 100.0, .max_landmarks = 100});
  window_only.update(0, Eigen::Vector3d::Zero(), {at(1, 1.0)});
  EXPECT_EQ(ids(window_only.update(kSecond, Eigen::Vector3d::Zero(), {at(2, 1.0)})), (std::vector<std::int64_t>{2}));

  LandmarkHorizon capped({.horizon_s = 10.0, .horizon_m = 100.0, .max_landmarks = 3});
  capped.update(0, Eigen::Vector3d::Zero(), {at(1, 1.0), at(2, 1.0)});
  capped.update(kSecond, Eigen::Vector3d::Zero(), {at(3, 1.0)});
  EXPECT_EQ(ids(capped.update(2 * kSecond, Eigen::Vector3d::Zero(), {at(4, 1.0), at(5, 1.0)})),
            (std::vector<std::int64_t>{3, 4, 5}));
}

TEST(LandmarkHorizon, BadConfigNamesTheKey) {
  try {
    LandmarkHorizonConfig c;
    c.horizon_m = -1.0;
    c.validate("estimator.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("local_map key 'horizon_m'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LandmarkHorizon({.horizon_s = -1.0}), InputError);
  EXPECT_THROW(LandmarkHorizon({.max_landmarks = 0}), InputError);
}

}  // namespace
}  // namespace twinslam::estimator

namespace twinslam::estimator {
namespace {

TEST(LandmarkHorizon, RememberedLandmarksMoveWithTheWindowsKeyframes) {
  // A fused registration moves the window 0.4 m north and turns it 2 deg: a landmark that left the window moves with
  // it, as it would have had it stayed in the window. Without follow_window it stays where it was.
  for (const bool follow : {true, false}) {
    LandmarkHorizon h({.horizon_s = 10.0, .horizon_m = 100.0, .max_landmarks = 100, .follow_window = follow});
    Eigen::Isometry3d k1 = Eigen::Isometry3d::Identity(), k2 = Eigen::Isometry3d::Identity();
    k1.translation() << 10, 0, 0;
    k2.translation() << 12, 0, 0;
    h.follow_window({{1 * kSecond, k1}, {2 * kSecond, k2}});
    h.update(2 * kSecond, k2.translation(), {at(5, 30.0), at(6, 31.0)});
    Eigen::Isometry3d moved(Eigen::Translation3d(0, 0.4, 0) * Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
    Eigen::Isometry3d k3 = Eigen::Isometry3d::Identity();
    k3.translation() << 14, 0, 0;
    // Keyframe 1 left the window; keyframe 2, the oldest in both, moved.
    h.follow_window({{2 * kSecond, moved * k2}, {3 * kSecond, k3}});
    const auto out = h.update(3 * kSecond, k3.translation(), {at(6, 31.5)});
    ASSERT_EQ(ids(out), (std::vector<std::int64_t>{5, 6}));
    const Eigen::Vector3d expected = follow ? Eigen::Vector3d(moved * Eigen::Vector3d(30, 0, 0)) : Eigen::Vector3d(30, 0, 0);
    EXPECT_LT((out[0].p_L - expected).norm(), 1e-12) << "follow_window " << follow;
    EXPECT_DOUBLE_EQ(out[1].p_L.x(), 31.5);  // still in the window: the window's own estimate
  }
}

TEST(LandmarkHorizon, WithCovariancesTheBestEstimateIsTheMostCertain) {
  // Quality saturates (5 deg of parallax) long before the depth is good far away: with covariances the remembered
  // estimate is the one with the smallest covariance, not the last at full quality.
  LandmarkHorizon h({.horizon_s = 10.0, .horizon_m = 100.0, .max_landmarks = 100});
  LandmarkEstimate a{1, Eigen::Vector3d(40, 0, 0), 1.0, Eigen::Matrix3d::Identity() * 0.04};
  LandmarkEstimate b{1, Eigen::Vector3d(41, 0, 0), 1.0, Eigen::Matrix3d::Identity() * 1.0};
  h.update(0, Eigen::Vector3d::Zero(), {a});
  h.update(kSecond, Eigen::Vector3d::Zero(), {b});
  const auto out = h.update(2 * kSecond, Eigen::Vector3d::Zero(), {});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].p_L.x(), 40.0);
  EXPECT_DOUBLE_EQ(out[0].cov_L(0, 0), 0.04);
}

}  // namespace
}  // namespace twinslam::estimator
