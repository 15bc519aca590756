#pragma once
// Trajectory files. All readers are strict (a silently skipped row is a hidden gap in an evaluation): a malformed row,
// a NaN, a quaternion whose norm is off by more than 1e-3, a timestamp that does not increase, or a file without poses
// is an InputError naming FILE:LINE.
#include <filesystem>

#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam {

// TUM RGB-D format: "t tx ty tz qx qy qz qw" per line, t in seconds (decimal), separated by blanks (commas accepted),
// '#' comment lines. Seconds are converted to integer nanoseconds exactly from the decimal text.
Trajectory read_tum(const std::filesystem::path& file);

// Writes TUM with 9 decimals on seconds (the full nanosecond stamp) and round-trip precision on all other numbers.
void write_tum(const std::filesystem::path& file, const Trajectory& trajectory);

// EuRoC ASL ground truth (mav0/state_groundtruth_estimate0/data.csv): #timestamp [ns], p_RS_R x y z [m],
// q_RS w x y z, then velocity and biases (ignored). R is the ground-truth reference frame, S the body (IMU).
Trajectory read_euroc_groundtruth(const std::filesystem::path& file);

// Ground truth of a dataset folder: DIR/groundtruth.tum if present, else the EuRoC CSV.
Trajectory read_dataset_groundtruth(const std::filesystem::path& dir);

// Estimate of a run folder: RUN/trajectory.tum.
Trajectory read_run_trajectory(const std::filesystem::path& dir);

// What the CLI accepts for --gt / --est: a dataset folder, a run folder, a .csv (EuRoC) or any other file (TUM).
Trajectory read_trajectory_any(const std::filesystem::path& path);

}  // namespace twinslam
