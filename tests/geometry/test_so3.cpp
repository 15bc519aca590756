// SO(3) maps and Jacobians: round trips at the delicate angles (0 and pi) and Jacobians against central differences.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "twinslam/geometry/so3.hpp"

namespace tg = twinslam::geometry;

namespace {

Eigen::Vector3d random_axis(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

bool is_rotation(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-12 && std::abs(R.determinant() - 1.0) < 1e-12;
}

// Column k: (Log(Exp(phi)^T Exp(phi + h e_k)) - Log(Exp(phi)^T Exp(phi - h e_k))) / 2h, which approximates Jr(phi) e_k.
Eigen::Matrix3d numeric_right_jacobian(const Eigen::Vector3d& phi) {
  const double h = 1e-6;
  const Eigen::Matrix3d R = tg::so3_exp(phi);
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(k);
    J.col(k) = (tg::so3_log(R.transpose() * tg::so3_exp(phi + e)) - tg::so3_log(R.transpose() * tg::so3_exp(phi - e))) /
               (2.0 * h);
  }
  return J;
}

}  // namespace

TEST(So3, SkewIsTheCrossProductAndVeeInvertsIt) {
  const Eigen::Vector3d a(0.3, -1.2, 2.0), b(-0.7, 0.4, 1.1);
  EXPECT_LT((tg::skew(a) * b - a.cross(b)).norm(), 1e-15);
  EXPECT_LT((tg::vee(tg::skew(a)) - a).norm(), 1e-15);
}

TEST(So3, ExpOfQuarterTurnAboutZ) {
  const Eigen::Matrix3d R = tg::so3_exp(Eigen::Vector3d(0, 0, M_PI / 2));
  EXPECT_LT((R * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
}

TEST(So3, ExpLogRoundTripNearZeroAndNearPi) {
  std::mt19937 rng(1);
  const double angles[] = {0.0, 1e-12, 1e-9, 1e-6, 9.9e-6, 1.01e-5, 1e-3, 0.5, 2.0,
                           M_PI - 1e-3, M_PI - 1e-6, M_PI - 1e-9, M_PI};
  for (double angle : angles) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d phi = angle * random_axis(rng);
      const Eigen::Matrix3d R = tg::so3_exp(phi);
      ASSERT_TRUE(is_rotation(R)) << angle;
      const Eigen::Vector3d back = tg::so3_log(R);
      EXPECT_LT((tg::so3_exp(back) - R).norm(), 1e-12) << "angle " << angle;
      EXPECT_NEAR(back.norm(), angle, 1e-12) << "angle " << angle;
      // Below pi the rotation vector itself is unique; at pi, phi and -phi are the same rotation.
      if (angle < M_PI - 1e-6) {
        EXPECT_LT((back - phi).norm(), 1e-12 * std::max(1.0, angle)) << angle;
      }
    }
  }
}

TEST(So3, LogOfHalfTurnHasAnglePi) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R(1, 1) = R(2, 2) = -1.0;  // 180 deg about x
  const Eigen::Vector3d phi = tg::so3_log(R);
  EXPECT_NEAR(phi.norm(), M_PI, 1e-12);
  EXPECT_NEAR(std::abs(phi.x()), M_PI, 1e-12);
}

TEST(So3, RightJacobianMatchesNumericDerivative) {
  std::mt19937 rng(2);
  const double angles[] = {0.0, 1e-7, 5e-6, 2e-5, 0.1, 1.0, 2.5, 3.0};
  for (double angle : angles) {
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::Vector3d phi = angle * random_axis(rng);
      const Eigen::Matrix3d Jr = tg::so3_right_jacobian(phi);
      EXPECT_LT((Jr - numeric_right_jacobian(phi)).norm(), 1e-8) << "angle " << angle;
      // Exp(phi + d) = Exp(phi) Exp(Jr d) to first order: the defining property, checked directly.
      const Eigen::Vector3d d = 1e-7 * random_axis(rng);
      EXPECT_LT((tg::so3_exp(phi + d) - tg::so3_exp(phi) * tg::so3_exp(Jr * d)).norm(), 1e-13) << angle;
    }
  }
}

TEST(So3, InverseRightJacobianInvertsAndLinearizesLog) {
  std::mt19937 rng(3);
  const double angles[] = {0.0, 1e-7, 5e-6, 2e-5, 0.1, 1.0, 2.5, 3.0};
  for (double angle : angles) {
    const Eigen::Vector3d phi = angle * random_axis(rng);
    const Eigen::Matrix3d Jinv = tg::so3_right_jacobian_inverse(phi);
    EXPECT_LT((Jinv * tg::so3_right_jacobian(phi) - Eigen::Matrix3d::Identity()).norm(), 1e-10) << angle;
    // Log(Exp(phi) Exp(d)) = phi + Jr^-1 d to first order (central difference over d).
    const double h = 1e-6;
    const Eigen::Matrix3d R = tg::so3_exp(phi);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(k);
      const Eigen::Vector3d col = (tg::so3_log(R * tg::so3_exp(e)) - tg::so3_log(R * tg::so3_exp(-e))) / (2 * h);
      EXPECT_LT((col - Jinv.col(k)).norm(), 1e-8) << angle;
    }
  }
}

TEST(So3, NormalizeRestoresOrthonormality) {
  Eigen::Matrix3d R = tg::so3_exp(Eigen::Vector3d(0.2, -0.4, 1.0));
  Eigen::Matrix3d noisy = R;
  noisy(0, 1) += 1e-6;
  noisy(2, 0) -= 2e-6;
  const Eigen::Matrix3d fixed = tg::so3_normalize(noisy);
  EXPECT_TRUE(is_rotation(fixed));
  EXPECT_LT(tg::so3_angle_between(fixed, R), 3e-6);
}
