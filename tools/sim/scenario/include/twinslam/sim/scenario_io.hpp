#pragma once
// Reading, validating and writing scenario files (CONTRACTS.md "Scenario file"), and the built-in scenarios.
// Every problem is an InputError "FILE[:LINE]: section.key: what", e.g. "scen.yaml:12: imu.rate_hz: must be > 0".
#include <filesystem>
#include <string>
#include <vector>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

// Names accepted by builtin_scenario(): tiny, city-loops, city-survey, city-long.
std::vector<std::string> builtin_scenario_names();

// A built-in scenario by name; UsageError for an unknown name (the message lists the known ones).
Scenario builtin_scenario(const std::string& name);

// `--scenario NAME|FILE.yaml`: a built-in name, else a YAML file. A file may start with `base: <built-in name>`; its
// keys then override that built-in's values. The result is validated and T_BC is filled.
Scenario load_scenario(const std::string& name_or_file);

// Parses YAML text (`file` only names it in messages) on top of `base` (or on top of the built-in named by its `base:`
// key). Unknown keys, wrong types and out-of-range values throw InputError naming `file` and the key.
Scenario parse_scenario_yaml(const std::string& text, const std::string& file, const Scenario& base = Scenario{});

// Range and consistency checks of every key; throws InputError "FILE: key: what". Used by the parser.
void validate_scenario(const Scenario& scenario, const std::string& file);

// The scenario as YAML (every key, numbers in shortest round-trip form): parse_scenario_yaml(scenario_to_yaml(s))
// gives back s. dataset.yaml echoes it.
std::string scenario_to_yaml(const Scenario& scenario);

// Camera extrinsics when the file gives none. loops/waypoints/streets: optical axis = body x (forward, horizontal;
// the loops yaw turns body x 45 deg toward the building); survey: optical axis pitched 45 deg down from body x
// (down-forward).
// Camera 10 cm ahead of and 5 cm below the IMU.
Eigen::Isometry3d default_T_BC(const std::string& trajectory_type);

// The extrinsics in effect: scenario.camera.T_BC if set, else default_T_BC(scenario.trajectory.type).
Eigen::Isometry3d camera_T_BC(const Scenario& scenario);

}  // namespace twinslam::sim
