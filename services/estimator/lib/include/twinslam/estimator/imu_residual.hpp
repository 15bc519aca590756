#pragma once
// The IMU preintegration residual between two keyframe states (Forster et al., TRO 2017, eq. 45, plus the bias random
// walk) and its Jacobians in closed form (Forster App. C), plus the state prediction it implies.
#include <Eigen/Core>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/preintegration.hpp"

namespace twinslam::estimator {

using Vector15d = Eigen::Matrix<double, 15, 1>;

// Jacobians of the (unweighted) residual w.r.t. tangent perturbations of the states:
//   p_L <- p_L + dp,  R_LB <- R_LB Exp(dtheta)  (right, i.e. body-frame, rotation perturbation),
//   v_L <- v_L + dv,  b_g <- b_g + dbg,  b_a <- b_a + dba.
// Columns: pose = [dp, dtheta], speed_bias = [dv, dbg, dba]. Rows: the residual order below.
struct ImuResidualJacobians {
  Eigen::Matrix<double, 15, 6> pose_i, pose_j;
  Eigen::Matrix<double, 15, 9> speed_bias_i, speed_bias_j;
};

// Residual r = [r_dR, r_dv, r_dp, r_bg, r_ba] (rad, m/s, m, rad/s, m/s^2), with the measurements corrected to the
// biases of state i (Forster eq. 44):
//   r_dR = Log(dR(b_i)^T R_i^T R_j)
//   r_dv = R_i^T (v_j - v_i - g dt) - dv(b_i)
//   r_dp = R_i^T (p_j - p_i - v_i dt - 1/2 g dt^2) - dp(b_i)
//   r_bg = b_g,j - b_g,i,   r_ba = b_a,j - b_a,i
// g_L is gravity in L [m/s^2], e.g. (0, 0, -9.81). Fills *jacobians when not null.
Vector15d imu_residual(const Preintegration& preintegration, const ImuState& state_i, const ImuState& state_j,
                       const Eigen::Vector3d& g_L, ImuResidualJacobians* jacobians = nullptr);

// State j that makes the residual zero given state i (the definition of the preintegrated measurements, Forster
// Sec. V-A, solved for state j, with the measurements corrected to the biases of state i):
//   R_j = R_i dR,  v_j = v_i + g dt + R_i dv,  p_j = p_i + v_i dt + 1/2 g dt^2 + R_i dp,  biases of state i.
ImuState predict(const ImuState& state_i, const Preintegration& preintegration, const Eigen::Vector3d& g_L);

}  // namespace twinslam::estimator
