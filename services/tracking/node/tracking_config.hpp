#pragma once
// The tracking service's config file (deploy/config/tracking.yaml): the FrontendConfig keys
// (frontend_config_yaml.hpp) plus a `node:` mapping for the DDS shell:
//   node:
//     imu_wait_ms: 100   # how long a frame may wait for IMU past its stamp [ms]
// The camera is not in the file: it comes from the dataset's sensor.yaml (--camera).
#include <string>

#include "tracking_node.hpp"
#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::tracking {

// Binds every key of the file to `options` (the frontend's keys and node:).
void bind_tracking_config(yaml::Fields& fields, TrackingNodeOptions& options);

// The keys that differ from the defaults ("max_features=120, clahe=true"), or "all defaults".
std::string changed_from_defaults(const TrackingNodeOptions& options);

// The YAML text over `base` (its camera is kept), validated; InputError naming `file`, the line and the key.
TrackingNodeOptions parse_tracking_config(const std::string& text, const std::string& file,
                                          const TrackingNodeOptions& base = {});
TrackingNodeOptions load_tracking_config(const std::string& path, const TrackingNodeOptions& base = {});

}  // namespace twinslam::tracking
