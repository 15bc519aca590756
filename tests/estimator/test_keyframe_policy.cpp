// Keyframe policy: rotation does not count as parallax, translation does, and losing tracks forces a keyframe.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/keyframe_policy.hpp"
#include "twinslam/geometry/so3.hpp"
#include "vision_test_utils.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

// 100 points 5-15 m in front of the keyframe camera C_k, observed again from camera C_c = (R_CkCc, t_CkCc).
std::vector<est::TrackedBearing> track(const Eigen::Matrix3d& R_CkCc, const Eigen::Vector3d& t_Ck, int n = 100) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<est::TrackedBearing> out;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p_Ck = (10.0 + 5.0 * u(rng)) * Eigen::Vector3d(0.5 * u(rng), 0.4 * u(rng), 1.0).normalized();
    const Eigen::Vector3d p_Cc = R_CkCc.transpose() * (p_Ck - t_Ck);
    out.push_back({p_Ck.normalized(), p_Cc.normalized()});
  }
  return out;
}

}  // namespace

TEST(KeyframePolicy, PureRotationIsNoParallax) {
  const Eigen::Matrix3d R = tg::so3_exp(Eigen::Vector3d(0.1, -0.2, 0.05));  // ~13 deg, ~100 px of image motion
  const auto tracked = track(R, Eigen::Vector3d::Zero());
  const est::KeyframeDecision d = est::decide_keyframe({}, {tracked, 100, R});
  EXPECT_FALSE(d.is_keyframe);
  EXPECT_LT(d.mean_parallax_px, 1e-9);
  // Without the compensation the same frame would look like a large parallax: the rotation must be given.
  EXPECT_GT(est::decide_keyframe({}, {tracked, 100, Eigen::Matrix3d::Identity()}).mean_parallax_px, 50.0);
}

TEST(KeyframePolicy, TranslationBeyondTheThresholdMakesAKeyframe) {
  const Eigen::Matrix3d R = tg::so3_exp(Eigen::Vector3d(0.0, 0.1, 0.0));
  // Sideways 5 cm at ~10 m: ~0.3 deg ~ 2.3 px mean, below 10 px. 40 cm: ~18 px, above.
  const auto small = est::decide_keyframe({}, {track(R, Eigen::Vector3d(0.05, 0, 0)), 100, R});
  EXPECT_FALSE(small.is_keyframe);
  EXPECT_NEAR(small.mean_parallax_px, 2.4, 0.8);
  const auto large = est::decide_keyframe({}, {track(R, Eigen::Vector3d(0.4, 0, 0)), 100, R});
  EXPECT_TRUE(large.is_keyframe);
  EXPECT_EQ(large.reason, est::KeyframeReason::kParallax);
  EXPECT_GT(large.mean_parallax_px, 10.0);
}

TEST(KeyframePolicy, LosingTracksMakesAKeyframe) {
  const auto tracked = track(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 40);
  const auto d = est::decide_keyframe({}, {tracked, 100, Eigen::Matrix3d::Identity()});
  EXPECT_TRUE(d.is_keyframe);
  EXPECT_EQ(d.reason, est::KeyframeReason::kTrackLoss);
  EXPECT_DOUBLE_EQ(d.tracked_ratio, 0.4);
  // Nothing tracked at all is the extreme case.
  EXPECT_EQ(est::decide_keyframe({}, {{}, 100, Eigen::Matrix3d::Identity()}).reason, est::KeyframeReason::kTrackLoss);
  // 60 of 100 tracked is above the 0.5 default.
  EXPECT_FALSE(est::decide_keyframe({}, {track(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 60), 100,
                                         Eigen::Matrix3d::Identity()})
                   .is_keyframe);
}

TEST(KeyframePolicyConfig, RejectsOutOfRangeValues) {
  est::KeyframePolicyConfig config;
  config.min_tracked_ratio = 1.5;
  EXPECT_THROW(config.validate(), twinslam::InputError);
  config = {};
  config.min_mean_parallax_px = 0.0;
  EXPECT_THROW(config.validate(), twinslam::InputError);
  EXPECT_NO_THROW(est::KeyframePolicyConfig{}.validate());
}
