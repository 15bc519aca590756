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
