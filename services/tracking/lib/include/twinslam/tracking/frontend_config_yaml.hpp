#pragma once
// FrontendConfig from YAML: one key per field, same names (deploy/config/tracking.yaml lists every key with its unit)
//   max_features: 180
//   ransac_model: essential    # or known_rotation
// The tracking service's file adds a `node:` mapping, read together with these keys by load_tracking_config
// (services/tracking/node/tracking_config.hpp).
#include <string>

#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/tracking/frontend_config.hpp"

namespace twinslam::tracking {

// Binds every key to `config` (one line per field: a new field of FrontendConfig is one line here).
void bind_frontend_config(yaml::Fields& fields, FrontendConfig& config);

// The YAML text over `base`, then validate(file); every error is an InputError naming `file` and the key.
FrontendConfig parse_frontend_config(const std::string& text, const std::string& file, const FrontendConfig& base = {});
FrontendConfig load_frontend_config(const std::string& path, const FrontendConfig& base = {});

}  // namespace twinslam::tracking
