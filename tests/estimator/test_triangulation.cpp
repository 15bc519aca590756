// Triangulation from bearings: exact recovery of noise-free points, and each rejection reason.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/triangulation.hpp"
#include "twinslam/geometry/so3.hpp"
#include "vision_test_utils.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

// Keyframes along a 1.5 m baseline looking roughly at a point 4-30 m ahead of the first camera, body rotated a bit
// between frames (rotation must not count as parallax).
struct Views {
  Eigen::Isometry3d T_BC = ts::forward_camera_T_BC();
  std::vector<est::BearingObservation> obs;
  Eigen::Vector3d p_L;

  Views(std::mt19937& rng, int n, double baseline_m, double depth_m) {
    const Eigen::Isometry3d T_LB0 = ts::random_pose(rng);
    const Eigen::Vector3d f_C0 = (Eigen::Vector3d::UnitZ() + ts::random_vector(rng, 0.3)).normalized();
    p_L = T_LB0 * T_BC * (depth_m * f_C0);
    for (int i = 0; i < n; ++i) {
      Eigen::Isometry3d T_LB = T_LB0;
      T_LB.translation() += T_LB0.linear() * Eigen::Vector3d(0.2, 1.0, 0.1).normalized() * (baseline_m * i / (n - 1));
      T_LB.linear() = T_LB0.linear() * tg::so3_exp(ts::random_vector(rng, 0.05));
      obs.push_back({T_LB, ((T_LB * T_BC).inverse() * p_L).normalized()});
    }
  }
};

}  // namespace

TEST(Triangulation, RecoversNoiseFreePointsFromThreeOrMoreViews) {
  std::mt19937 rng(21);
  const est::TriangulationConfig config;
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 3 + trial % 4;
    const double depth = 4.0 + 26.0 * std::uniform_real_distribution<double>(0, 1)(rng);
    const Views v(rng, n, 1.5, depth);
    const std::size_t anchor = static_cast<std::size_t>(trial) % n;
    const auto result = est::triangulate(config, v.obs, v.T_BC, anchor);
    ASSERT_TRUE(result.ok()) << est::to_string(result.status) << " trial " << trial;
    const Eigen::Vector3d p_Ca = (v.obs[anchor].T_LB * v.T_BC).inverse() * v.p_L;
    EXPECT_NEAR(result.rho, 1.0 / p_Ca.norm(), 1e-9 / p_Ca.norm()) << trial;
    EXPECT_LT((result.p_L - v.p_L).norm(), 1e-9 * depth) << trial;
    EXPECT_LT(result.max_error_px, 1e-6);
  }
}

TEST(Triangulation, WorksWithFisheyeBearingsBeyondNinetyDegrees) {
  // A point beside the cameras: about 100 deg off the optical axis of a forward camera moving forward.
  const Eigen::Isometry3d T_BC = ts::forward_camera_T_BC();
  const Eigen::Vector3d p_L(-1.0, 6.0, 0.3);  // to the left and slightly behind the first camera (body x forward)
  std::vector<est::BearingObservation> obs;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Isometry3d T_LB = twinslam::geometry::make_pose(Eigen::Matrix3d::Identity(),
                                                                 Eigen::Vector3d(0.7 * i, 0, 0));
    obs.push_back({T_LB, ((T_LB * T_BC).inverse() * p_L).normalized()});
  }
  ASSERT_LT(obs[0].f_C.z(), 0.0);  // really behind the image plane
  const auto result = est::triangulate(est::TriangulationConfig{}, obs, T_BC);
  ASSERT_TRUE(result.ok()) << est::to_string(result.status);
  EXPECT_LT((result.p_L - p_L).norm(), 1e-9);
}

TEST(Triangulation, RejectsLowParallax) {
  std::mt19937 rng(22);
  // 5 cm of baseline at 30 m: 0.1 deg of parallax, below the 1 deg default.
  const Views v(rng, 3, 0.05, 30.0);
  const auto result = est::triangulate(est::TriangulationConfig{}, v.obs, v.T_BC);
  EXPECT_EQ(result.status, est::TriangulationStatus::kLowParallax);
  EXPECT_NEAR(result.parallax_deg, 0.05 / 30.0 * 57.3, 0.05);
  // Pure rotation has no parallax at all, however large the rotation.
  std::vector<est::BearingObservation> rotated{v.obs[0], v.obs[0]};
  rotated[1].T_LB.linear() = rotated[0].T_LB.linear() * tg::so3_exp(Eigen::Vector3d(0.0, 0.3, 0.0));
  rotated[1].f_C = ((rotated[1].T_LB * v.T_BC).inverse() * v.p_L).normalized();
  EXPECT_EQ(est::triangulate(est::TriangulationConfig{}, rotated, v.T_BC).status,
            est::TriangulationStatus::kLowParallax);
}

TEST(Triangulation, RejectsAnOutlierObservation) {
  std::mt19937 rng(23);
  Views v(rng, 4, 1.5, 10.0);
  // One observation 3 deg off (about 24 px at 460 px/rad).
  v.obs[2].f_C = tg::so3_exp(Eigen::Vector3d(0.0, 0.05, 0.0)) * v.obs[2].f_C;
  const auto result = est::triangulate(est::TriangulationConfig{}, v.obs, v.T_BC);
  EXPECT_EQ(result.status, est::TriangulationStatus::kLargeError);
  EXPECT_GT(result.max_error_px, 3.0);
}

TEST(Triangulation, RejectsPointsBehindTheCamerasAndOutOfRange) {
  std::mt19937 rng(24);
  Views v(rng, 3, 1.5, 10.0);
  std::vector<est::BearingObservation> flipped = v.obs;
  for (auto& o : flipped) o.f_C = -o.f_C;  // rays meet behind every camera
  EXPECT_EQ(est::triangulate(est::TriangulationConfig{}, flipped, v.T_BC).status,
            est::TriangulationStatus::kBehindCamera);
  est::TriangulationConfig near_only;
  near_only.max_depth_m = 5.0;
  EXPECT_EQ(est::triangulate(near_only, v.obs, v.T_BC).status, est::TriangulationStatus::kDepthOutOfRange);
  EXPECT_EQ(est::triangulate(near_only, std::span(v.obs).first(1), v.T_BC).status,
            est::TriangulationStatus::kTooFewViews);
}

TEST(TriangulationConfig, RejectsInconsistentValues) {
  est::TriangulationConfig config;
  config.max_depth_m = 0.05;
  EXPECT_THROW(config.validate(), twinslam::InputError);
  config = {};
  config.min_parallax_deg = -1.0;
  EXPECT_THROW(config.validate(), twinslam::InputError);
  EXPECT_NO_THROW(est::TriangulationConfig{}.validate());
}
