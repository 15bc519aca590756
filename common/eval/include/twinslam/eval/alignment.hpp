#pragma once
// Alignment of an estimate to the ground truth before the absolute error is taken (Zhang & Scaramuzza, IROS 2018,
// Sec. III/IV): the unobservable degrees of freedom of the estimator are removed, nothing else.
//   none   - the estimate is already in the ground-truth frame W (twinslam with GNSS or twin registration)
//   posyaw - 4-DoF, yaw + translation: visual-inertial odometry (gravity makes roll and pitch observable)
//   se3    - 6-DoF rigid: e.g. stereo visual odometry
//   sim3   - 7-DoF rigid + scale: monocular visual odometry
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

namespace twinslam::eval {

enum class AlignMode { None, PosYaw, SE3, Sim3 };

std::string to_string(AlignMode mode);
// "none" | "posyaw" | "se3" | "sim3"; anything else is a UsageError listing the choices.
AlignMode parse_align_mode(std::string_view text);

// S_WL: maps the estimate's frame L to the ground-truth frame W, p_W = scale * R_WL * p_L + t_W.
struct Similarity {
  double scale = 1.0;
  Eigen::Matrix3d R_WL = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_W = Eigen::Vector3d::Zero();  // [m]

  Eigen::Vector3d apply(const Eigen::Vector3d& p_L) const { return scale * R_WL * p_L + t_W; }
  // T_WB from T_LB: rotation composed, position mapped (scale applies to positions only).
  Eigen::Isometry3d apply(const Eigen::Isometry3d& T_LB) const;
};

// Umeyama (1991), "Least-squares estimation of transformation parameters between two point patterns", eqs. 34-43:
// the (R, t[, s]) minimizing sum |p_W - (s R p_L + t)|^2. Needs >= 3 non-collinear point pairs.
Similarity umeyama(const std::vector<Eigen::Vector3d>& p_L, const std::vector<Eigen::Vector3d>& p_W, bool with_scale);

// Closed-form 4-DoF alignment: rotation about z only. With centred points x (estimate) and y (ground truth) the cost
// is minimal at yaw = atan2(sum(x_x y_y - x_y y_x), sum(x_x y_x + x_y y_y)), then t = mean(y) - R_z mean(x).
Similarity align_posyaw(const std::vector<Eigen::Vector3d>& p_L, const std::vector<Eigen::Vector3d>& p_W);

// Alignment of the estimate poses T_LB to the ground truth poses T_WB (pairs, same order) by `mode`. With a single pair
// posyaw and se3 use the orientation of that pose as well (as rpg_trajectory_evaluation does for "first frame");
// too few pairs for the mode is an InputError.
Similarity align(AlignMode mode, const std::vector<Eigen::Isometry3d>& T_LB, const std::vector<Eigen::Isometry3d>& T_WB);

}  // namespace twinslam::eval
