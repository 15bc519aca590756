#pragma once
// Landmarks of the sliding window as anchored inverse depth.
//
// Why this parameterization: a landmark is stored as the unit bearing f_Ca of its first observation in the camera C_a
// of an anchor keyframe (a constant, not optimized) plus one inverse depth rho [1/m] along it, p_Ca = f_Ca / rho.
//  - One optimized parameter per landmark instead of three (VINS-Mono, Qin et al., TRO 2018, Sec. VI, uses the same
//    "inverse depth in the first observing frame"; OKVIS keeps homogeneous points for the same reason): the Schur
//    complement of the landmarks is cheap and the anchor observation is satisfied exactly, by construction.
//  - Well conditioned at low parallax and for far points: the reprojection error is close to linear in rho, and a
//    point at infinity is rho = 0, a finite value, while depth or Euclidean coordinates diverge (Civera, Davison,
//    Montiel, "Inverse Depth Parametrization for Monocular SLAM", TRO 2008, and its linearity analysis).
// The price: when the anchor keyframe leaves the window the landmark must be re-anchored (reanchor()) before the anchor
// is marginalized, as VINS-Mono does when it slides the window.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::estimator {

// Size of the landmark's Ceres parameter block: [rho] (Euclidean, 1/m).
inline constexpr int kInverseDepthSize = 1;

struct InverseDepthLandmark {
  std::int64_t id = -1;
  std::int64_t anchor_keyframe = -1;                       // keyframe whose camera C_a anchors the landmark
  Eigen::Vector3d f_Ca = Eigen::Vector3d::UnitZ();         // unit bearing in C_a (the anchor observation)
  double rho = 0.1;                                        // inverse depth along f_Ca [1/m]: p_Ca = f_Ca / rho
};

// T_LB of a pose parameter block [p_L, q_LB xyzw] (imu_state.hpp); the quaternion is normalized.
Eigen::Isometry3d pose_from_block(const double* pose);

// p_L = T_LB_a T_BC (f_Ca / rho) [m]. rho must be > 0 (a point at infinity has no position).
Eigen::Vector3d point_in_local(const Eigen::Isometry3d& T_LBa, const Eigen::Isometry3d& T_BC,
                               const Eigen::Vector3d& f_Ca, double rho);

// Inverse depth of the point of the ray (C_a, f_Ca) closest to p_L: rho = 1 / (f_Ca . p_Ca). Empty when p_L is not in
// front of C_a along f_Ca (depth <= 0).
std::optional<double> inverse_depth_along(const Eigen::Isometry3d& T_LBa, const Eigen::Isometry3d& T_BC,
                                          const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& p_L);

// Covariance [m^2] in L of the point p_L = c_a + u_a / rho of a landmark (c_a: anchor camera centre, u_a: unit anchor
// ray, both in L) from the bearing noise `bearing_sigma_rad` of its observations from the camera centres
// `observers_L`, the poses taken as known. Along the ray: sigma_depth = sigma_rho / rho^2 with
// 1 / sigma_rho^2 = sum_k |d b_k / d rho|^2 / sigma_b^2, where b_k is the unit bearing from camera k and
// |d b_k / d rho| = |(I - b_k b_k^T) u_a| / (rho^2 |p - c_k|) (zero for the anchor itself); two cameras a baseline b
// apart, square to the ray at depth d, give the familiar sigma_depth = d^2 sigma_b / b. Across the ray: d sigma_b (the
// anchor observation). Without parallax the depth sigma is capped at the depth itself.
Eigen::Matrix3d landmark_covariance_L(const Eigen::Vector3d& c_a, const Eigen::Vector3d& u_a, double rho,
                                      const std::vector<Eigen::Vector3d>& observers_L, double bearing_sigma_rad);

// Moves `landmark` to a new anchor keyframe whose observation of it is f_Cn (unit bearing in the new anchor camera):
// the current point estimate p_L is kept as well as the new ray allows (closest point on the ray). Empty when the point
// is not in front of the new anchor.
std::optional<InverseDepthLandmark> reanchor(const InverseDepthLandmark& landmark, const Eigen::Isometry3d& T_LB_old,
                                             const Eigen::Isometry3d& T_LB_new, const Eigen::Isometry3d& T_BC,
                                             std::int64_t new_anchor_keyframe, const Eigen::Vector3d& f_Cn);

}  // namespace twinslam::estimator
