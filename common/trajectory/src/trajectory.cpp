#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam {

StampedPose make_pose(std::int64_t stamp_ns, const Eigen::Vector3d& p_X, const Eigen::Quaterniond& q_XB) {
  StampedPose pose;
  pose.stamp_ns = stamp_ns;
  pose.T_XB.linear() = q_XB.normalized().toRotationMatrix();
  pose.T_XB.translation() = p_X;
  return pose;
}

double path_length(const Trajectory& trajectory) {
  double length_m = 0.0;
  for (std::size_t i = 1; i < trajectory.poses.size(); ++i) {
    length_m += (trajectory.poses[i].p_X() - trajectory.poses[i - 1].p_X()).norm();
  }
  return length_m;
}

}  // namespace twinslam
