#pragma once
// Absolute trajectory error (Zhang & Scaramuzza, IROS 2018, Sec. IV-A) on associated, aligned pose pairs:
// position error |p_gt - p_est| [m], rotation error = angle of R_gt^T R_est [deg].
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/eval/stats.hpp"

namespace twinslam::eval {

struct AteResult {
  std::vector<double> pos_err_m;    // per pair
  std::vector<double> rot_err_deg;  // per pair
  ErrorStats pos;                   // [m]
  ErrorStats rot;                   // [deg]
};

// T_WB_gt[i] and T_WB_est[i] are the same instant; the estimate is already aligned into W.
AteResult compute_ate(const std::vector<Eigen::Isometry3d>& T_WB_gt, const std::vector<Eigen::Isometry3d>& T_WB_est);

// Angle of a rotation [deg], accurate for small angles (through the quaternion, not acos of the trace).
double rotation_angle_deg(const Eigen::Matrix3d& R);

}  // namespace twinslam::eval
