// Quality and covariance of the window's landmarks (window_landmarks): what registration filters and weights by.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "twinslam/estimator/landmark.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"

namespace twinslam::estimator {
namespace {

// A window of keyframes on a line along x (identity attitude, camera = body), each seeing the point p_L.
WindowState window_seeing(const Eigen::Vector3d& p_L, const std::vector<double>& x_m, double parallax_at_init_deg) {
  WindowState s;
  s.config.T_BC = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    auto f = std::make_unique<WindowFrame>();
    f->id = static_cast<std::int64_t>(i);
    f->keyframe = true;
    f->pose = {x_m[i], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    f->bearings[7] = (p_L - Eigen::Vector3d(x_m[i], 0.0, 0.0)).normalized();
    s.frames.push_back(std::move(f));
  }
  WindowLandmark lm;
  lm.lm.id = 7;
  lm.lm.anchor_keyframe = 0;
  lm.lm.f_Ca = s.frames.front()->bearings.at(7);
  lm.rho = lm.lm.rho = 1.0 / (p_L - Eigen::Vector3d(x_m[0], 0.0, 0.0)).norm();
  lm.parallax_deg = parallax_at_init_deg;
  s.landmarks.emplace(7, lm);
  return s;
}

TEST(LandmarkQuality, ParallaxIsThatOfTheKeyframesObservingItNowNotAtTriangulation) {
  // Triangulated from the first two keyframes 0.5 m apart (1.4 deg at 20 m), then seen over 4 m (11 deg): as well
  // determined as any point, so full quality. Judged by its triangulation parallax it stayed at 0.29 for life, and
  // registration (min_quality 0.5) had too few points for the first minute of city-loops.
  const Eigen::Vector3d p_L(0.0, 0.0, 20.0);
  const auto out = window_landmarks(window_seeing(p_L, {0.0, 0.5, 1.0, 2.0, 3.0, 4.0}, 1.43));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].quality, 1.0);
  EXPECT_LT((out[0].p_L - p_L).norm(), 1e-9);
}

TEST(LandmarkQuality, ShortBaselineAndFewObserversStayPoor) {
  // Two observers 0.5 m apart at 20 m: 1.4 deg of parallax (q 0.29) and one observation beyond the anchor (q 0.25).
  const auto out = window_landmarks(window_seeing(Eigen::Vector3d(0.0, 0.0, 20.0), {0.0, 0.5}, 1.43));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].quality, 0.25 * std::atan(0.5 / 20.0) * 180.0 / M_PI / 5.0, 1e-6);
  // A landmark whose anchor left the window is not reported.
  WindowState s = window_seeing(Eigen::Vector3d(0.0, 0.0, 20.0), {0.0, 0.5, 1.0}, 1.43);
  s.frames.pop_front();
  EXPECT_TRUE(window_landmarks(s).empty());
}

}  // namespace
}  // namespace twinslam::estimator

namespace twinslam::estimator {
namespace {

// Unit bearing from camera centre c to the point c_a + u_a / rho.
Eigen::Vector3d bearing(const Eigen::Vector3d& c_a, const Eigen::Vector3d& u_a, double rho, const Eigen::Vector3d& c) {
  return (c_a + u_a / rho - c).normalized();
}

TEST(LandmarkCovariance, TwoViewsSquareToTheRayGiveTheTextbookDepthSigma) {
  // Two cameras b = 1 m apart, the point d = 20 m ahead of the first: sigma_depth = d^2 sigma_b / b (to first order in
  // b / d), across the ray d sigma_b.
  const double d = 20.0, b = 1.0, sigma_b = 1e-3;
  const Eigen::Vector3d c_a = Eigen::Vector3d::Zero(), u_a = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d C = landmark_covariance_L(c_a, u_a, 1.0 / d, {c_a, Eigen::Vector3d(b, 0, 0)}, sigma_b);
  const double along = std::sqrt(u_a.dot(C * u_a)), across = std::sqrt(C(0, 0));
  EXPECT_NEAR(along, d * d * sigma_b / b, 0.01 * d * d * sigma_b / b);  // 0.4 m
  EXPECT_NEAR(across, d * sigma_b, 1e-12);
  EXPECT_NEAR(C(0, 2), 0.0, 1e-12);  // axes of the ray
  // No second view (or none off the ray): no depth information, capped at the depth itself.
  const Eigen::Matrix3d none = landmark_covariance_L(c_a, u_a, 1.0 / d, {c_a, Eigen::Vector3d(0, 0, -3)}, sigma_b);
  EXPECT_NEAR(std::sqrt(none(2, 2)), d, 1e-9);
}

TEST(LandmarkCovariance, DepthSigmaIsTheInverseOfTheNumericBearingInformation) {
  // Four cameras around, the point 35 m out: 1 / sigma_rho^2 = sum |d b_k / d rho|^2 / sigma_b^2 by central differences.
  const Eigen::Vector3d c_a(1, 2, 3), u_a = Eigen::Vector3d(0.3, 0.9, 0.1).normalized();
  const double rho = 1.0 / 35.0, sigma_b = 2e-3, h = 1e-7;
  const std::vector<Eigen::Vector3d> cams{c_a, {3, 2, 3}, {1, 5, 4}, {-2, 0, 3.5}};
  double info = 0.0;
  for (const auto& c : cams) {
    const Eigen::Vector3d db = (bearing(c_a, u_a, rho + h, c) - bearing(c_a, u_a, rho - h, c)) / (2 * h);
    info += db.squaredNorm() / (sigma_b * sigma_b);
  }
  const double sigma_depth = 1.0 / (rho * rho * std::sqrt(info));
  const Eigen::Matrix3d C = landmark_covariance_L(c_a, u_a, rho, cams, sigma_b);
  EXPECT_NEAR(std::sqrt(u_a.dot(C * u_a)), sigma_depth, 1e-4 * sigma_depth);
  EXPECT_LT((C - C.transpose()).norm(), 1e-15);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues().minCoeff(), 0.0);
}

TEST(LandmarkCovariance, TheWindowReportsItWithEveryLandmark) {
  // The window of the first test (keyframes over 4 m, the point 20 m out): its depth sigma is that of those views.
  const Eigen::Vector3d p_L(0.0, 0.0, 20.0);
  WindowState s = window_seeing(p_L, {0.0, 0.5, 1.0, 2.0, 3.0, 4.0}, 1.43);
  s.config.pixel_sigma = 1.0;
  s.config.focal_px = 500.0;
  const auto out = window_landmarks(s);
  ASSERT_EQ(out.size(), 1u);
  std::vector<Eigen::Vector3d> cams;
  for (double x : {0.0, 0.5, 1.0, 2.0, 3.0, 4.0}) cams.emplace_back(x, 0.0, 0.0);
  const Eigen::Matrix3d expected = landmark_covariance_L(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0 / 20.0,
                                                         cams, 1.0 / 500.0);
  EXPECT_LT((out[0].cov_L - expected).norm(), 1e-9 * expected.norm());
  EXPECT_GT(std::sqrt(out[0].cov_L(2, 2)), 0.05);  // ~0.1 m deep at 20 m over 4 m
  EXPECT_LT(std::sqrt(out[0].cov_L(2, 2)), 0.2);
}

}  // namespace
}  // namespace twinslam::estimator
