// Quaternion helpers and SE(3) maps.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "twinslam/geometry/quaternion.hpp"
#include "twinslam/geometry/se3.hpp"
#include "twinslam/geometry/so3.hpp"

namespace tg = twinslam::geometry;

TEST(Quaternion, ExpAndLogAgreeWithTheMatrixMaps) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double scale : {0.0, 1e-9, 1e-4, 0.7, 1.8}) {
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::Vector3d phi = scale * Eigen::Vector3d(u(rng), u(rng), u(rng));
      const Eigen::Quaterniond q = tg::quaternion_exp(phi);
      EXPECT_NEAR(q.norm(), 1.0, 1e-15);
      EXPECT_LT((q.toRotationMatrix() - tg::so3_exp(phi)).norm(), 1e-14);
      EXPECT_LT((tg::quaternion_log(q) - phi).norm(), 1e-14);
      // -q is the same rotation: the log must not change.
      EXPECT_LT((tg::quaternion_log(Eigen::Quaterniond(-q.coeffs())) - phi).norm(), 1e-14);
    }
  }
}

TEST(Quaternion, CanonicalHasNonNegativeScalarAndUnitNorm) {
  const Eigen::Quaterniond q(-2.0, 0.2, -0.4, 1.0);
  const Eigen::Quaterniond c = tg::canonical(q);
  EXPECT_GE(c.w(), 0.0);
  EXPECT_NEAR(c.norm(), 1.0, 1e-15);
  EXPECT_LT((c.toRotationMatrix() - q.normalized().toRotationMatrix()).norm(), 1e-14);
}

TEST(Quaternion, RightPerturbationJacobianMatchesNumericDerivative) {
  // dtheta(dq) = Log(q^-1 (x) normalize(q + dq)); the analytic 3x4 matrix must be its derivative, also for a
  // quaternion that is slightly off the unit sphere (as stored parameter blocks can be).
  for (const Eigen::Quaterniond& q : {Eigen::Quaterniond(0.3, -0.5, 0.7, 0.1), Eigen::Quaterniond(-0.9, 0.1, 0.0, 0.2),
                                     Eigen::Quaterniond(1.0, 0.0, 0.0, 0.0)}) {
    const Eigen::Quaterniond qs(q.coeffs() * 1.001);
    const Eigen::Matrix<double, 3, 4> J = tg::right_perturbation_jacobian(qs);
    const double h = 1e-7;
    for (int k = 0; k < 4; ++k) {
      Eigen::Quaterniond plus = qs, minus = qs;
      plus.coeffs()[k] += h;
      minus.coeffs()[k] -= h;
      const Eigen::Quaterniond qn = qs.normalized();
      const Eigen::Vector3d num = (tg::quaternion_log(qn.conjugate() * plus.normalized()) -
                                   tg::quaternion_log(qn.conjugate() * minus.normalized())) /
                                  (2 * h);
      EXPECT_LT((J.col(k) - num).norm(), 1e-8) << "column " << k;
    }
    // Scaling the quaternion does not rotate anything.
    EXPECT_LT((J * qs.coeffs()).norm(), 1e-14);
  }
}

TEST(Se3, ExpLogRoundTripAndKnownPose) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    tg::Vector6d xi;
    for (int k = 0; k < 6; ++k) xi[k] = 2.0 * u(rng);
    const Eigen::Isometry3d T = tg::se3_exp(xi);
    EXPECT_LT((tg::se3_log(T) - xi).norm(), 1e-12);
  }
  // A pure translation is its own log.
  tg::Vector6d xi = tg::Vector6d::Zero();
  xi.head<3>() << 1.0, -2.0, 3.0;
  EXPECT_LT((tg::se3_exp(xi).translation() - Eigen::Vector3d(1.0, -2.0, 3.0)).norm(), 1e-15);
}

TEST(Se3, RelativePoseMapsBetweenFrames) {
  const Eigen::Isometry3d T_WA = tg::make_pose(tg::so3_exp(Eigen::Vector3d(0, 0, M_PI / 2)), Eigen::Vector3d(1, 0, 0));
  const Eigen::Isometry3d T_WB = tg::make_pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 0));
  const Eigen::Isometry3d T_AB = tg::relative_pose(T_WA, T_WB);
  // B sits 2 m along W's y, which is A's x axis.
  EXPECT_LT((T_AB.translation() - Eigen::Vector3d(2, 0, 0)).norm(), 1e-15);
  EXPECT_NEAR(tg::rotation_distance(T_WA, T_WB), M_PI / 2, 1e-15);
  EXPECT_NEAR(tg::translation_distance(T_WA, T_WB), 2.0, 1e-15);
}

TEST(Se3, InterpolateHalfwayHalvesAngleAndTranslation) {
  const Eigen::Isometry3d T_a = tg::make_pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  const Eigen::Isometry3d T_b = tg::make_pose(tg::so3_exp(Eigen::Vector3d(0, 1.0, 0)), Eigen::Vector3d(4, 0, 2));
  const Eigen::Isometry3d T_m = tg::interpolate_pose(T_a, T_b, 0.5);
  EXPECT_LT((tg::so3_log(T_m.linear()) - Eigen::Vector3d(0, 0.5, 0)).norm(), 1e-14);
  EXPECT_LT((T_m.translation() - Eigen::Vector3d(2, 0, 1)).norm(), 1e-15);
}
