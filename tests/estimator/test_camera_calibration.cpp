// CameraRotationFactor (online R_BC calibration): analytic Jacobians against numeric ones, including the rotation
// block away from phi = 0; the same residual as ReprojectionFactor; zero at the true mounting.
#include <random>

#include <gtest/gtest.h>

#include "twinslam/estimator/camera_calibration.hpp"
#include "twinslam/geometry/quaternion.hpp"
#include "twinslam/geometry/so3.hpp"
#include "vision_test_utils.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

// A landmark seen by an anchor and an observer whose camera is mounted at R_BC0 Exp(phi_true).
struct Scene {
  double pose_a[7], pose_j[7], rho, phi[3];
  Eigen::Vector3d f_Ca, f_Cj;
  Eigen::Isometry3d T_BC0 = ts::forward_camera_T_BC();

  Scene(std::mt19937& rng, const Eigen::Vector3d& phi_true) {
    const Eigen::Isometry3d T_BC = est::calibrated_T_BC(T_BC0, phi_true.data());
    const Eigen::Isometry3d T_LBj = ts::random_pose(rng);
    Eigen::Isometry3d T_LBa = T_LBj;
    T_LBa.translation() += ts::random_vector(rng, 1.0);
    T_LBa.linear() = T_LBj.linear() * tg::so3_exp(ts::random_vector(rng, 0.3));
    const Eigen::Vector3d p_Cj = Eigen::Vector3d(0.2, -0.1, 1.0).normalized() * 8.0 + ts::random_vector(rng, 1.0);
    const Eigen::Vector3d p_Ca = (T_LBa * T_BC).inverse() * (T_LBj * T_BC * p_Cj);
    f_Ca = p_Ca.normalized();
    f_Cj = p_Cj.normalized();
    rho = 1.0 / p_Ca.norm();
    ts::pack_pose(T_LBa, pose_a);
    ts::pack_pose(T_LBj, pose_j);
    Eigen::Map<Eigen::Vector3d>{phi} = phi_true;
  }
  std::vector<double*> params() { return {pose_a, pose_j, &rho, phi}; }
};

}  // namespace

TEST(CameraRotationFactor, AnalyticJacobiansMatchNumericIncludingTheRotationBlock) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 20; ++trial) {
    // Away from the truth and from phi = 0, where the right Jacobian of SO(3) matters.
    Scene s(rng, ts::random_vector(rng, 0.05));
    for (int k = 0; k < 3; ++k) s.phi[k] += ts::random_vector(rng, 0.02)[k];
    s.rho *= 1.1;
    const est::CameraRotationFactor factor(s.f_Ca, (s.f_Cj + ts::random_vector(rng, 0.01)).normalized(), s.T_BC0,
                                           460.0);
    const auto analytic = ts::analytic_jacobians(factor, s.params());
    const auto numeric = ts::numeric_jacobians(factor, s.params());
    for (int b = 0; b < 4; ++b) {
      EXPECT_LT(ts::max_relative_error(analytic[b], numeric[b]), 1e-6) << "trial " << trial << " block " << b
                                                                       << "\nanalytic\n" << analytic[b]
                                                                       << "\nnumeric\n" << numeric[b];
    }
  }
}

TEST(CameraRotationFactor, VanishesAtTheTrueMountingAndEqualsTheFixedFactor) {
  std::mt19937 rng(32);
  const Eigen::Vector3d phi_true(0.01, -0.008, 0.012);  // about 0.8 deg
  Scene s(rng, phi_true);
  const est::CameraRotationFactor calibrated(s.f_Ca, s.f_Cj, s.T_BC0, 460.0);
  Eigen::Vector2d r;
  const std::vector<double*> p = s.params();
  ASSERT_TRUE(calibrated.Evaluate(p.data(), r.data(), nullptr));
  EXPECT_LT(r.norm(), 1e-9);
  // With the nominal mounting the point reprojects off by the mounting error; the fixed factor built on the true
  // mounting agrees with the calibrated one at every state.
  const est::ReprojectionFactor fixed(s.f_Ca, s.f_Cj, est::calibrated_T_BC(s.T_BC0, phi_true.data()), 460.0);
  s.pose_j[0] += 0.1;
  Eigen::Vector2d r_cal, r_fixed;
  ASSERT_TRUE(calibrated.Evaluate(p.data(), r_cal.data(), nullptr));
  ASSERT_TRUE(fixed.Evaluate(p.data(), r_fixed.data(), nullptr));
  EXPECT_LT((r_cal - r_fixed).norm(), 1e-9);
  EXPECT_GT(r_cal.norm(), 1.0);
}

TEST(CameraRotationFactor, PriorIsWhitenedByItsSigmaAndRefusesZero) {
  const auto prior = est::new_camera_rotation_prior(0.01);
  const double phi[3] = {0.02, 0.0, -0.01};
  const double* p[1] = {phi};
  Eigen::Vector3d r;
  ASSERT_TRUE(prior->Evaluate(p, r.data(), nullptr));
  EXPECT_NEAR(r.x(), 2.0, 1e-12);
  EXPECT_NEAR(r.z(), -1.0, 1e-12);
  EXPECT_THROW(est::new_camera_rotation_prior(0.0), std::invalid_argument);
}
