#pragma once
// A trajectory is a time-ordered list of poses T_XB of the body B (IMU) in some frame X: the world W for ground truth
// and for `RUN/trajectory.tum`, the local odometry frame L for `trajectory_local.tum`. The frame is not stored: the
// file a trajectory comes from says which one it is (CONTRACTS.md, "Run outputs").
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace twinslam {

struct StampedPose {
  std::int64_t stamp_ns = 0;                         // sensor time [ns]
  Eigen::Isometry3d T_XB = Eigen::Isometry3d::Identity();  // body B in frame X; translation in metres

  Eigen::Vector3d p_X() const { return T_XB.translation(); }
  Eigen::Quaterniond q_XB() const { return Eigen::Quaterniond(T_XB.linear()); }
};

struct Trajectory {
  std::vector<StampedPose> poses;  // strictly increasing stamp_ns (the readers guarantee it)
  std::string source;              // file it was read from, for messages ("" when built in memory)

  std::size_t size() const { return poses.size(); }
  bool empty() const { return poses.empty(); }
};

// Builds a pose from a position [m] and a unit quaternion (w, x, y, z); the quaternion is normalized here so that a
// file's rounding to 6 decimals does not leave a slightly non-orthogonal rotation matrix.
StampedPose make_pose(std::int64_t stamp_ns, const Eigen::Vector3d& p_X, const Eigen::Quaterniond& q_XB);

// Sum of the distances between consecutive positions [m].
double path_length(const Trajectory& trajectory);

}  // namespace twinslam
