#include "twinslam/eval/ate.hpp"

#include <cmath>

namespace twinslam::eval {

double rotation_angle_deg(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  // 2 atan2(|v|, |w|) is well conditioned everywhere, unlike acos((tr R - 1) / 2) near 0.
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())) * 180.0 / M_PI;
}

AteResult compute_ate(const std::vector<Eigen::Isometry3d>& T_WB_gt, const std::vector<Eigen::Isometry3d>& T_WB_est) {
  AteResult out;
  out.pos_err_m.reserve(T_WB_gt.size());
  out.rot_err_deg.reserve(T_WB_gt.size());
  for (std::size_t i = 0; i < T_WB_gt.size(); ++i) {
    out.pos_err_m.push_back((T_WB_gt[i].translation() - T_WB_est[i].translation()).norm());
    out.rot_err_deg.push_back(rotation_angle_deg(T_WB_gt[i].linear().transpose() * T_WB_est[i].linear()));
  }
  out.pos = compute_stats(out.pos_err_m);
  out.rot = compute_stats(out.rot_err_deg);
  return out;
}

}  // namespace twinslam::eval
