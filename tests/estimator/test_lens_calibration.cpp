// LensCalibrationFactor (online correction of the intrinsics in bearing space): the correction model against a real
// equidistant lens whose stated calibration is off, analytic Jacobians against numeric ones, and the factor's
// agreement with the plain ReprojectionFactor built on the true bearings.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "twinslam/estimator/lens_calibration.hpp"
#include "vision_test_utils.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;

namespace {

// The equidistant (Kannala-Brandt, k1 only) lens of the simulator: pixel = f theta (1 + k1 theta^2) u + c.
struct Lens {
  double f, k1;
  Eigen::Vector2d c;
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    const double r = p.head<2>().norm(), theta = std::atan2(r, p.z());
    return f * theta * (1.0 + k1 * theta * theta) * p.head<2>() / r + c;
  }
  Eigen::Vector3d unproject(const Eigen::Vector2d& px) const {
    const Eigen::Vector2d m = (px - c) / f;
    const double d = m.norm();
    double theta = d;
    for (int i = 0; i < 20; ++i) {  // Newton on theta (1 + k1 theta^2) = d
      theta -= (theta * (1.0 + k1 * theta * theta) - d) / (1.0 + 3.0 * k1 * theta * theta);
    }
    Eigen::Vector3d out;
    out.head<2>() = std::sin(theta) * m / d;
    out.z() = std::cos(theta);
    return out;
  }
};

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace

TEST(LensCalibration, TheCorrectionOfAWrongStatedLensGivesTheTrueBearings) {
  // A checkerboard calibration's residual, as the simulator's defaults: focal 0.3 %, principal point 1 px, k1 0.002.
  const Lens truth{305.0, 0.01, {320.0, 200.0}};
  const Lens stated{305.0 * 0.997, 0.01 - 0.002, {321.0, 199.5}};
  const double c[4] = {-0.003, -0.002, 1.0 / 305.0, -0.5 / 305.0};  // stated fu/true - 1, k1 stated - true, dc / f
  double worst_stated = 0.0, worst_corrected = 0.0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    // Up to 60 deg off the axis (a 120 deg fisheye).
    const double theta = 1.047 * std::abs(u(rng)), phi = M_PI * u(rng);
    const Eigen::Vector3d f_true(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const Eigen::Vector3d f_stated = stated.unproject(truth.project(f_true));
    worst_stated = std::max(worst_stated, angle(f_stated, f_true));
    worst_corrected = std::max(worst_corrected, angle(est::corrected_bearing(f_stated, c), f_true));
  }
  std::printf("worst bearing error: stated %.3f px, corrected %.4f px\n", worst_stated * 305.0,
              worst_corrected * 305.0);
  EXPECT_GT(worst_stated * 305.0, 1.5);     // the stated lens bends bearings by pixels off-axis
  EXPECT_LT(worst_corrected * 305.0, 0.1);  // first-order c: what is left is second order in the errors
  // No correction, no change (the axis included).
  const double zero[4] = {0, 0, 0, 0};
  EXPECT_LT(angle(est::corrected_bearing(Eigen::Vector3d(0.3, -0.2, 0.9).normalized(), zero),
                  Eigen::Vector3d(0.3, -0.2, 0.9).normalized()), 1e-15);
  EXPECT_LT(angle(est::corrected_bearing(Eigen::Vector3d::UnitZ(), zero), Eigen::Vector3d::UnitZ()), 1e-15);
}

TEST(LensCalibration, BearingJacobianMatchesNumericOnAndOffTheAxis) {
  const double c[4] = {0.004, -0.003, 0.002, -0.001};
  for (const Eigen::Vector3d& f : {Eigen::Vector3d(0.3, -0.2, 0.9), Eigen::Vector3d(0.8, 0.5, 0.3),
                                   Eigen::Vector3d(1e-9, 0.0, 1.0), Eigen::Vector3d(0.9, 0.1, -0.2)}) {
    Eigen::Matrix<double, 3, est::kLensSize> J;
    est::corrected_bearing(f, c, &J);
    for (int k = 0; k < est::kLensSize; ++k) {
      double cp[4] = {c[0], c[1], c[2], c[3]}, cm[4] = {c[0], c[1], c[2], c[3]};
      cp[k] += 1e-7;
      cm[k] -= 1e-7;
      const Eigen::Vector3d numeric = (est::corrected_bearing(f, cp) - est::corrected_bearing(f, cm)) / 2e-7;
      EXPECT_LT((J.col(k) - numeric).norm(), 1e-7) << "f " << f.transpose() << " column " << k;
    }
  }
}

TEST(LensCalibrationFactor, AnalyticJacobiansMatchNumeric) {
  std::mt19937 rng(41);
  const Eigen::Isometry3d T_BC = ts::forward_camera_T_BC();
  for (int trial = 0; trial < 20; ++trial) {
    double pose_a[7], pose_j[7], rho = 0.08 + 0.02 * trial / 20.0, c[4];
    const Eigen::Isometry3d T_LBj = ts::random_pose(rng);
    Eigen::Isometry3d T_LBa = T_LBj;
    T_LBa.translation() += ts::random_vector(rng, 1.0);
    ts::pack_pose(T_LBa, pose_a);
    ts::pack_pose(T_LBj, pose_j);
    Eigen::Map<Eigen::Vector4d>{c} = Eigen::Vector4d::Random() * 0.005;
    const Eigen::Vector3d f_Ca = (Eigen::Vector3d(0.4, -0.3, 1.0) + ts::random_vector(rng, 0.3)).normalized();
    const Eigen::Vector3d f_Cj = (Eigen::Vector3d(-0.2, 0.5, 1.0) + ts::random_vector(rng, 0.3)).normalized();
    const est::LensCalibrationFactor factor(f_Ca, f_Cj, T_BC, 460.0);
    const std::vector<double*> params{pose_a, pose_j, &rho, c};
    const auto analytic = ts::analytic_jacobians(factor, params);
    const auto numeric = ts::numeric_jacobians(factor, params);
    for (int b = 0; b < 4; ++b) {
      EXPECT_LT(ts::max_relative_error(analytic[b], numeric[b]), 1e-6) << "trial " << trial << " block " << b
                                                                       << "\nanalytic\n" << analytic[b]
                                                                       << "\nnumeric\n" << numeric[b];
    }
  }
}

TEST(LensCalibrationFactor, EqualsTheFixedFactorOnTheCorrectedBearingsAtItsZero) {
  // At the observation the residual vanishes exactly when the prediction is the corrected observed bearing, and the
  // angular error is the fixed factor's on the corrected bearings.
  std::mt19937 rng(42);
  const Eigen::Isometry3d T_BC = ts::forward_camera_T_BC();
  const double c[4] = {-0.003, -0.002, 0.003, -0.001};
  const Eigen::Isometry3d T_LBj = ts::random_pose(rng);
  Eigen::Isometry3d T_LBa = T_LBj;
  T_LBa.translation() += Eigen::Vector3d(0.5, -0.3, 0.2);
  const Eigen::Vector3d p_Cj = Eigen::Vector3d(0.6, -0.4, 1.0).normalized() * 9.0;
  const Eigen::Vector3d p_Ca = (T_LBa * T_BC).inverse() * (T_LBj * T_BC * p_Cj);
  // The stated bearings are those that the correction turns into the true ones (its inverse to first order).
  const double minus_c[4] = {-c[0], -c[1], -c[2], -c[3]};
  const Eigen::Vector3d f_Ca = est::corrected_bearing(p_Ca.normalized(), minus_c);
  const Eigen::Vector3d f_Cj = est::corrected_bearing(p_Cj.normalized(), minus_c);
  double pose_a[7], pose_j[7], rho = 1.0 / p_Ca.norm();
  ts::pack_pose(T_LBa, pose_a);
  ts::pack_pose(T_LBj, pose_j);
  const est::LensCalibrationFactor factor(f_Ca, f_Cj, T_BC, 460.0);
  const est::ReprojectionFactor stated(f_Ca, f_Cj, T_BC, 460.0);
  const double zero[4] = {0, 0, 0, 0};
  EXPECT_GT(stated.angular_error(pose_a, pose_j, rho) * 460.0, 0.1);  // the stated lens misses (0.14 px here)
  EXPECT_NEAR(factor.angular_error(pose_a, pose_j, rho, zero), stated.angular_error(pose_a, pose_j, rho), 1e-12);
  EXPECT_LT(factor.angular_error(pose_a, pose_j, rho, c) * 460.0, 0.02);
  EXPECT_TRUE(factor.in_front(pose_a, pose_j, rho, c));
  Eigen::Vector2d r;
  const double* params[4] = {pose_a, pose_j, &rho, c};
  ASSERT_TRUE(factor.Evaluate(params, r.data(), nullptr));
  EXPECT_LT(r.norm(), 0.02);
}
