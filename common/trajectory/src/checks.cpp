#include "checks.hpp"

#include <cmath>

#include "twinslam/core/error.hpp"

namespace twinslam::detail {

void check_unit_quaternion(const std::filesystem::path& file, std::size_t line, const Eigen::Quaterniond& q) {
  const double norm = q.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    throw InputError(where(file.string(), line,
                           "quaternion is not normalized (|q| = " + std::to_string(norm) + ")"));
  }
}

void append_increasing(const std::filesystem::path& file, std::size_t line, Trajectory& trajectory,
                       const StampedPose& pose) {
  if (!trajectory.poses.empty() && pose.stamp_ns <= trajectory.poses.back().stamp_ns) {
    throw InputError(where(file.string(), line,
                           "timestamp " + std::to_string(pose.stamp_ns) + " ns does not increase (previous " +
                               std::to_string(trajectory.poses.back().stamp_ns) + " ns)"));
  }
  trajectory.poses.push_back(pose);
}

void check_not_empty(const std::filesystem::path& file, const Trajectory& trajectory) {
  if (trajectory.poses.empty()) throw InputError(where(file.string(), 0, "no poses in file"));
}

}  // namespace twinslam::detail
