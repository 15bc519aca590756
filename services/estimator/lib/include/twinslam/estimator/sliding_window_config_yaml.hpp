#pragma once
// SlidingWindowConfig from YAML: the top-level keys are the struct's fields, the nested structs are mappings
//   window_keyframes: 8
//   keyframe: {min_mean_parallax_px: 10.0, min_tracked_ratio: 0.5}
//   triangulation: {...}   marginalization: {...}   motion_init: {...}
// (deploy/config/estimator.yaml lists every key with its unit). Not in the file: the camera (focal_px, T_BC) and the
// IMU noise, which come from the dataset's sensor.yaml files (--camera, --imu), and the copies the estimator fills in
// itself (keyframe.focal_px, triangulation.focal_px, motion_init.pixel_sigma). The service's file adds a `node:`
// mapping, read together with these keys by load_estimator_service_config (services/estimator/node).
#include <string>

#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/estimator/sliding_window_config.hpp"

namespace twinslam::estimator {

// Binds every key of the file to `config` (one line per field: a new field of SlidingWindowConfig is one line here).
void bind_sliding_window_config(yaml::Fields& fields, SlidingWindowConfig& config);

// The YAML text over `base`, then validate(); every error is an InputError naming `file` and the key.
SlidingWindowConfig parse_estimator_config(const std::string& text, const std::string& file,
                                           const SlidingWindowConfig& base = {});
SlidingWindowConfig load_estimator_config(const std::string& path, const SlidingWindowConfig& base = {});

// config.validate(), its message prefixed with `file` ("estimator.yaml: sliding_window.max_landmarks: must be >= 1").
void validate_estimator_config(const SlidingWindowConfig& config, const std::string& file);

}  // namespace twinslam::estimator
