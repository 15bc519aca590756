#include "twinslam/estimator/imu_residual.hpp"

#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {

namespace g = twinslam::geometry;

Vector15d imu_residual(const Preintegration& pre, const ImuState& si, const ImuState& sj, const Eigen::Vector3d& g_L,
                       ImuResidualJacobians* J) {
  const double dt = pre.dt();
  const PreintegratedDelta d = pre.corrected(si.bias);
  // Normalizing here makes the residual a function of the rotation only, so scaling a stored quaternion has no
  // effect and the ambient Jacobian has no radial part (see geometry::right_perturbation_jacobian).
  const Eigen::Matrix3d Ri = si.q_LB.normalized().toRotationMatrix();
  const Eigen::Matrix3d Rj = sj.q_LB.normalized().toRotationMatrix();
  const Eigen::Matrix3d RiT = Ri.transpose();

  const Eigen::Matrix3d E = d.R.transpose() * RiT * Rj;  // rotation error, identity at the optimum
  const Eigen::Vector3d w_v = sj.v_L - si.v_L - g_L * dt;
  const Eigen::Vector3d w_p = sj.p_L - si.p_L - si.v_L * dt - 0.5 * g_L * dt * dt;

  Vector15d r;
  r.segment<3>(0) = g::so3_log(E);
  r.segment<3>(3) = RiT * w_v - d.v;
  r.segment<3>(6) = RiT * w_p - d.p;
  r.segment<3>(9) = sj.bias.gyro - si.bias.gyro;
  r.segment<3>(12) = sj.bias.accel - si.bias.accel;
  if (J == nullptr) return r;

  // Forster App. C, with Euclidean position/velocity perturbations in L (instead of Forster's p + R dp, which only
  // changes the position columns to -R_i^T / R_i^T here).
  const PreintegrationBiasJacobians& jb = pre.bias_jacobians();
  const Eigen::Vector3d dbg = si.bias.gyro - pre.linearization_bias().gyro;
  const Eigen::Matrix3d Jr_inv = g::so3_right_jacobian_inverse(r.segment<3>(0));
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();

  J->pose_i.setZero();
  J->pose_j.setZero();
  J->speed_bias_i.setZero();
  J->speed_bias_j.setZero();

  // d r / d pose_i = [dp_i, dtheta_i]
  J->pose_i.block<3, 3>(0, 3) = -Jr_inv * Rj.transpose() * Ri;
  J->pose_i.block<3, 3>(3, 3) = g::skew(RiT * w_v);
  J->pose_i.block<3, 3>(6, 0) = -RiT;
  J->pose_i.block<3, 3>(6, 3) = g::skew(RiT * w_p);

  // d r / d speed_bias_i = [dv_i, dbg_i, dba_i]. The rotation term differentiates Exp(dR_dbg dbg) through the right
  // Jacobian at dR_dbg dbg (Forster App. C): -Jr^-1(r) Exp(r)^T Jr(dR_dbg dbg) dR_dbg.
  J->speed_bias_i.block<3, 3>(0, 3) = -Jr_inv * E.transpose() * g::so3_right_jacobian(jb.dR_dbg * dbg) * jb.dR_dbg;
  J->speed_bias_i.block<3, 3>(3, 0) = -RiT;
  J->speed_bias_i.block<3, 3>(3, 3) = -jb.dv_dbg;
  J->speed_bias_i.block<3, 3>(3, 6) = -jb.dv_dba;
  J->speed_bias_i.block<3, 3>(6, 0) = -RiT * dt;
  J->speed_bias_i.block<3, 3>(6, 3) = -jb.dp_dbg;
  J->speed_bias_i.block<3, 3>(6, 6) = -jb.dp_dba;
  J->speed_bias_i.block<3, 3>(9, 3) = -I;
  J->speed_bias_i.block<3, 3>(12, 6) = -I;

  // d r / d pose_j and d r / d speed_bias_j
  J->pose_j.block<3, 3>(0, 3) = Jr_inv;
  J->pose_j.block<3, 3>(6, 0) = RiT;
  J->speed_bias_j.block<3, 3>(3, 0) = RiT;
  J->speed_bias_j.block<3, 3>(9, 3) = I;
  J->speed_bias_j.block<3, 3>(12, 6) = I;
  return r;
}

ImuState predict(const ImuState& si, const Preintegration& pre, const Eigen::Vector3d& g_L) {
  const double dt = pre.dt();
  const PreintegratedDelta d = pre.corrected(si.bias);
  const Eigen::Matrix3d Ri = si.q_LB.normalized().toRotationMatrix();
  ImuState sj;
  sj.q_LB = Eigen::Quaterniond(Ri * d.R).normalized();
  sj.v_L = si.v_L + g_L * dt + Ri * d.v;
  sj.p_L = si.p_L + si.v_L * dt + 0.5 * g_L * dt * dt + Ri * d.p;
  sj.bias = si.bias;
  return sj;
}

}  // namespace twinslam::estimator
