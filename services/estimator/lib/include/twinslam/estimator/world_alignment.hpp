#pragma once
// The alignment T_WL of the estimator's local frame L to the world W (East-North-Up at the dataset origin) as a state
// of the sliding window. L and W are both gravity-aligned, so T_WL has 4 degrees of freedom (paper eq. 11):
// T_WL = (Rz(yaw_WL), p_WL).
//
// Parameter block (kWorldAlignmentSize = 4, Euclidean): [p_WL x, y, z [m], yaw_WL [rad]] (translation first).
//
// Gauge (docs/ARCHITECTURE.md): L keeps the definition the initialization gives it — the first keyframe's prior pins
// L's position and yaw, and marginalization carries that forward — and global measurements act on T_WB = T_WL T_LB
// through this block. VIO-only runs never touch it (it stays out of the problem, held at its value), so their
// trajectories are unchanged; W-frame terms estimate T_WL and, through it, correct the window's drift in L.
#include <ceres/cost_function.h>
#include <Eigen/Geometry>

namespace twinslam::estimator {

inline constexpr int kWorldAlignmentSize = 4;

// The block's pose T_WL and back (the latter keeps the yaw of T_WL's rotation: its heading, atan2(R(1,0), R(0,0)),
// dropping any roll/pitch).
Eigen::Isometry3d world_alignment_pose(const double* T_WL_block);
void set_world_alignment_block(const Eigen::Isometry3d& T_WL, double* T_WL_block);

// p_W = Rz(yaw_WL) p_L + p_WL, templated for automatic differentiation in providers' cost functions.
template <class T>
void world_from_local(const T* T_WL_block, const T* p_L, T* p_W) {
  using std::cos;
  using std::sin;
  const T c = cos(T_WL_block[3]), s = sin(T_WL_block[3]);
  p_W[0] = c * p_L[0] - s * p_L[1] + T_WL_block[0];
  p_W[1] = s * p_L[0] + c * p_L[1] + T_WL_block[1];
  p_W[2] = p_L[2] + T_WL_block[2];
}

struct WorldAlignmentSigmas {
  double position_m = 1.0;  // [m], each axis
  double yaw_rad = 0.05;    // [rad]
  void validate() const;    // throws twinslam::InputError unless both are finite and > 0
};

// Residual (4): [(p_WL - p0) / sigma_p; wrap(yaw_WL - yaw0) / sigma_yaw]. Block: T_WL [4]. Caller owns the result.
ceres::CostFunction* new_world_alignment_prior(const Eigen::Isometry3d& T_WL0, const WorldAlignmentSigmas& sigmas);

}  // namespace twinslam::estimator
