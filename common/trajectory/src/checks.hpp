#pragma once
// Validation shared by all readers, so every format rejects the same things with the same words.
#include <filesystem>
#include <optional>

#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::detail {

// Largest accepted | |q| - 1 |: files round quaternions to ~6 decimals, anything beyond 1e-3 is a broken row.
constexpr double kQuaternionNormTolerance = 1e-3;

// Throws InputError(FILE:LINE) if q is not unit within tolerance.
void check_unit_quaternion(const std::filesystem::path& file, std::size_t line, const Eigen::Quaterniond& q);

// Appends a pose, throwing InputError(FILE:LINE) if its stamp does not increase over the last one.
void append_increasing(const std::filesystem::path& file, std::size_t line, Trajectory& trajectory,
                       const StampedPose& pose);

// Throws InputError(FILE) if the trajectory has no pose.
void check_not_empty(const std::filesystem::path& file, const Trajectory& trajectory);

}  // namespace twinslam::detail
