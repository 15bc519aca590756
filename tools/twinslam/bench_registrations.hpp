#pragma once
// How far accepted registrations put their keyframe from the truth (issue 12: "no accepted registration whose
// correction is wrong by more than 0.5 m", twin changes). Read from RUN/registrations.csv: the keyframe pose the
// LocalMap carried in W (kf_* columns) moved by the correction (dx dy dz, droll dpitch dyaw) is the pose the
// registration measured; both are compared with the ground truth at the keyframe's stamp.
#include <cstddef>
#include <filesystem>
#include <optional>

#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::cli {

struct RegistrationTruth {
  std::size_t accepted = 0;  // accepted registrations of keyframes that were in W, matched to the truth
  std::size_t off = 0;       // ... of which the measured position is farther than threshold_m from the truth
  double threshold_m = 0.5;
  double median_before_m = 0, median_after_m = 0, max_after_m = 0;  // position error of the estimate / measurement
  double median_after_deg = 0, max_after_deg = 0;                   // rotation error of the measurement
};

// Evaluates RUN/registrations.csv against `gt` and writes RUN/registration_errors.csv (one row per evaluated
// registration: stamp_ns, before_m, after_m, after_deg, after error in W ex ey ez [m]). nullopt when the run has no
// accepted registration of a keyframe in W. Bad rows throw InputError naming the file and line.
std::optional<RegistrationTruth> evaluate_registrations(const std::filesystem::path& run_dir, const Trajectory& gt,
                                                        double threshold_m = 0.5);

}  // namespace twinslam::cli
