// The test trajectory's closed-form derivatives must agree with finite differences, or every IMU test built on it
// would check against the wrong truth.
#include <gtest/gtest.h>

#include "analytic_trajectory.hpp"
#include "twinslam/geometry/so3.hpp"

using twinslam::testing::AnalyticTrajectory;

TEST(AnalyticTrajectory, DerivativesMatchFiniteDifferences) {
  const AnalyticTrajectory traj;
  const double h = 1e-5;
  for (double t : {0.0, 0.7, 2.3, 5.1, 11.9}) {
    const auto s = traj.at(t), a = traj.at(t - h), b = traj.at(t + h);
    EXPECT_LT((s.v_W - (b.p_W - a.p_W) / (2 * h)).norm(), 1e-8) << t;
    EXPECT_LT((s.a_W - (b.v_W - a.v_W) / (2 * h)).norm(), 1e-8) << t;
    // omega_B = vee(R^T dR/dt): the rotation from t-h to t+h is Exp(2 h omega_B) to second order.
    const Eigen::Vector3d omega_num = twinslam::geometry::so3_log(a.R_WB.transpose() * b.R_WB) / (2 * h);
    EXPECT_LT((s.omega_B - omega_num).norm(), 1e-8) << t;
  }
}

TEST(AnalyticTrajectory, MovesLikeADrone) {
  // Guards the test premise: enough motion that a wrong integrator shows, yet rates a real IMU sees.
  const AnalyticTrajectory traj;
  double max_rate = 0.0, max_acc = 0.0;
  for (double t = 0.0; t < 10.0; t += 0.01) {
    const auto s = traj.at(t);
    max_rate = std::max(max_rate, s.omega_B.norm());
    max_acc = std::max(max_acc, s.a_W.norm());
  }
  EXPECT_GT(max_rate, 0.3);
  EXPECT_LT(max_rate, 2.0);
  EXPECT_GT(max_acc, 0.5);
  EXPECT_LT(max_acc, 5.0);
}
