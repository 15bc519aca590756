#pragma once
// Evaluation figures (PNG) for one or several estimates against one ground truth.
#include <filesystem>
#include <string>
#include <vector>

#include "twinslam/eval/evaluate.hpp"
#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::eval {

struct PlotRun {
  std::string label;           // legend entry, e.g. "estimate" or the mode "vio-twin"
  const EvalResult* result;    // aligned poses, errors and RPE samples of that estimate
};

// Creates `dir` and writes, returning the written files:
//   trajectory_xy.png  top-down view (x east, y north) of the ground truth and every aligned estimate
//   trajectory_xz.png  side view (x, z)
//   error_position.png ATE position error [m] over time [s since the first ground-truth stamp]
//   error_rotation.png ATE rotation error [deg] over time
//   rpe_translation.png / rpe_rotation.png  RPE box plots per segment length ([%], [deg/m])
// An unwritable folder is an InputError.
std::vector<std::filesystem::path> write_eval_plots(const std::filesystem::path& dir, const Trajectory& gt,
                                                    const std::vector<PlotRun>& runs);

}  // namespace twinslam::eval
