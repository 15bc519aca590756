#pragma once
// The estimator service's config file (deploy/config/estimator.yaml): the SlidingWindowConfig keys
// (sliding_window_config_yaml.hpp) plus a `node:` mapping for the DDS shell:
//   node:
//     imu_wait_ms: 100                  # how long a frame may wait for IMU past its stamp [ms]
//     lockstep_max_solver_time_s: 1.0   # solver time cap per frame under --max [s]
#include <string>

#include "estimator_node.hpp"
#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::estimator {

struct EstimatorServiceConfig {
  EstimatorNodeOptions options;  // options.estimator: the window; T_BC, focal_px, imu still come from --camera/--imu
  // Under lockstep replay (--max) this replaces max_solver_time_s. CONTRACTS.md promises repeatable trajectories
  // there (two runs within 1 mm); a tight wall-clock cap would make the result depend on the machine's load, so the
  // cap is far above any solve's time and only max_solver_iterations bounds the work [s].
  double lockstep_max_solver_time_s = 1.0;

  // The options to run with: under lockstep, max_solver_time_s = lockstep_max_solver_time_s.
  EstimatorNodeOptions for_replay(bool lockstep) const;
};

// Binds every key of the file to `config` (the window's keys and node:).
void bind_estimator_service_config(yaml::Fields& fields, EstimatorServiceConfig& config);

// The keys that differ from the defaults ("window_keyframes=10, node.imu_wait_ms=50"), or "all defaults".
std::string changed_from_defaults(const EstimatorServiceConfig& config);

// The YAML text over `base`, validated; InputError naming `file`, the line where there is one, and the key.
EstimatorServiceConfig parse_estimator_service_config(const std::string& text, const std::string& file,
                                                      const EstimatorServiceConfig& base = {});
EstimatorServiceConfig load_estimator_service_config(const std::string& path, const EstimatorServiceConfig& base = {});

}  // namespace twinslam::estimator
