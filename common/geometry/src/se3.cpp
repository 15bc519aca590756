#include "twinslam/geometry/se3.hpp"

#include "twinslam/geometry/so3.hpp"

namespace twinslam::geometry {

Eigen::Isometry3d se3_exp(const Vector6d& xi) {
  const Eigen::Vector3d rho = xi.head<3>();
  const Eigen::Vector3d phi = xi.tail<3>();
  return make_pose(so3_exp(phi), so3_left_jacobian(phi) * rho);
}

Vector6d se3_log(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d phi = so3_log(T.linear());
  Vector6d xi;
  // Jl is invertible for angles below 2 pi; a 3x3 solve is cheaper to get right than the closed-form inverse.
  xi.head<3>() = so3_left_jacobian(phi).lu().solve(T.translation());
  xi.tail<3>() = phi;
  return xi;
}

Eigen::Isometry3d interpolate_pose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b, double alpha) {
  const Eigen::Quaterniond q_a(T_a.linear());
  const Eigen::Quaterniond q_b(T_b.linear());
  return make_pose(q_a.slerp(alpha, q_b), (1.0 - alpha) * T_a.translation() + alpha * T_b.translation());
}

double translation_distance(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b) {
  return (T_a.translation() - T_b.translation()).norm();
}

double rotation_distance(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b) {
  return so3_angle_between(T_a.linear(), T_b.linear());
}

}  // namespace twinslam::geometry
