#pragma once
// SE(3) helpers on Eigen::Isometry3d. T_AB maps coordinates in B to A: p_A = T_AB * p_B.
// Tangent vectors are ordered xi = [rho; phi] (translation part first, then rotation vector [rad]).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::geometry {

using Vector6d = Eigen::Matrix<double, 6, 1>;

inline Eigen::Isometry3d make_pose(const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_A) {
  Eigen::Isometry3d T_AB = Eigen::Isometry3d::Identity();
  T_AB.linear() = R_AB;
  T_AB.translation() = p_A;
  return T_AB;
}
inline Eigen::Isometry3d make_pose(const Eigen::Quaterniond& q_AB, const Eigen::Vector3d& p_A) {
  return make_pose(q_AB.normalized().toRotationMatrix(), p_A);
}

// T_AB = T_WA^-1 T_WB: pose of B seen from A.
inline Eigen::Isometry3d relative_pose(const Eigen::Isometry3d& T_WA, const Eigen::Isometry3d& T_WB) {
  return T_WA.inverse() * T_WB;
}

// exp of the se(3) element [rho; phi]: rotation Exp(phi), translation Jl(phi) rho (Barfoot, State Estimation for
// Robotics, eq. 7.85).
Eigen::Isometry3d se3_exp(const Vector6d& xi);
// Inverse of se3_exp (rotation angle in [0, pi]).
Vector6d se3_log(const Eigen::Isometry3d& T);

// Interpolation between two poses at alpha in [0, 1]: slerp of the rotation and a straight line for the translation,
// which is how trajectories sampled at sensor rates are resampled to other timestamps.
Eigen::Isometry3d interpolate_pose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b, double alpha);

// Errors between two poses of the same frame: translation distance [m] and rotation angle [rad].
double translation_distance(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b);
double rotation_distance(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b);

}  // namespace twinslam::geometry
