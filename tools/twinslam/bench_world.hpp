#pragma once
// What `twinslam bench` reports about a world-frame mode's start (issue 12): when T_WB entered W, how far the pose in
// W was from the truth 10 s after the first estimate (the paper's initial-alignment accuracy, 0.50 m / 0.79 deg), and
// the LocalMap -> Registration latency the run measured.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::cli {

struct WorldStart {
  std::int64_t aligned_from_stamp_ns = 0;  // first pose in W
  double aligned_after_s = 0.0;            // ... seconds after the first estimate
  // Error of the estimate in W at the first pose >= 10 s after the first estimate (and in W), against the ground
  // truth pose nearest in time: position [m] and rotation angle [deg]. Unset if the run has no such pose.
  std::optional<double> error_at_10s_m, error_at_10s_deg;
  std::optional<double> latency_median_ms, latency_p99_ms;  // run.json registration_latency_ms, if any
  // run.json out_of_world_ns: stretches [first, last] (stamps, ns) after the alignment whose poses were not in W.
  std::vector<std::pair<std::int64_t, std::int64_t>> out_of_world_ns;
};

// Reads RUN/run.json; nullopt if the run never aligned to W. `est` is the run's trajectory.tum, `gt` the truth.
std::optional<WorldStart> read_world_start(const std::filesystem::path& run_dir, const Trajectory& gt,
                                           const Trajectory& est);

// Keeps the poses of `est` that are in W: from the alignment on, outside the out-of-world stretches.
void keep_world_poses(Trajectory& est, const WorldStart& start);

}  // namespace twinslam::cli
