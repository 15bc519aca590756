#include "twinslam/estimator/landmark.hpp"

#include <cmath>

#include "twinslam/geometry/se3.hpp"

namespace twinslam::estimator {

Eigen::Isometry3d pose_from_block(const double* pose) {
  const Eigen::Map<const Eigen::Quaterniond> q_LB(pose + 3);
  return geometry::make_pose(q_LB, Eigen::Map<const Eigen::Vector3d>(pose));
}

Eigen::Vector3d point_in_local(const Eigen::Isometry3d& T_LBa, const Eigen::Isometry3d& T_BC,
                               const Eigen::Vector3d& f_Ca, double rho) {
  return T_LBa * (T_BC * (f_Ca / rho));
}

std::optional<double> inverse_depth_along(const Eigen::Isometry3d& T_LBa, const Eigen::Isometry3d& T_BC,
                                          const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& p_L) {
  const Eigen::Vector3d p_Ca = (T_LBa * T_BC).inverse() * p_L;
  const double depth = f_Ca.normalized().dot(p_Ca);  // [m] along the ray
  if (!(depth > 0.0) || !std::isfinite(depth)) return std::nullopt;
  return 1.0 / depth;
}

Eigen::Matrix3d landmark_covariance_L(const Eigen::Vector3d& c_a, const Eigen::Vector3d& u_a, double rho,
                                      const std::vector<Eigen::Vector3d>& observers_L, double bearing_sigma_rad) {
  const double depth = 1.0 / rho;
  const Eigen::Vector3d p = c_a + u_a * depth;
  double info_rho = 0.0;  // [m^2 / sigma_b^2]
  for (const Eigen::Vector3d& c : observers_L) {
    const double range = (p - c).norm();
    if (!(range > 0.0)) continue;
    const Eigen::Vector3d b = (p - c) / range;
    const double rate = (u_a - b * b.dot(u_a)).norm() / (rho * rho * range);  // |d b / d rho| [rad m]
    info_rho += rate * rate;
  }
  info_rho /= bearing_sigma_rad * bearing_sigma_rad;
  const double sigma_depth = info_rho > 0.0 ? std::min(1.0 / (rho * rho * std::sqrt(info_rho)), depth) : depth;
  const double sigma_across = depth * bearing_sigma_rad;
  const Eigen::Matrix3d along = u_a * u_a.transpose();
  return sigma_depth * sigma_depth * along + sigma_across * sigma_across * (Eigen::Matrix3d::Identity() - along);
}

std::optional<InverseDepthLandmark> reanchor(const InverseDepthLandmark& landmark, const Eigen::Isometry3d& T_LB_old,
                                             const Eigen::Isometry3d& T_LB_new, const Eigen::Isometry3d& T_BC,
                                             std::int64_t new_anchor_keyframe, const Eigen::Vector3d& f_Cn) {
  const Eigen::Vector3d p_L = point_in_local(T_LB_old, T_BC, landmark.f_Ca, landmark.rho);
  const Eigen::Vector3d f = f_Cn.normalized();
  const auto rho = inverse_depth_along(T_LB_new, T_BC, f, p_L);
  if (!rho) return std::nullopt;
  InverseDepthLandmark out = landmark;
  out.anchor_keyframe = new_anchor_keyframe;
  out.f_Ca = f;
  out.rho = *rho;
  return out;
}

}  // namespace twinslam::estimator
