#pragma once
// The bridge service's config (`twinslam-bridge --config FILE.yaml`; command-line options win).
#include <string>

namespace twinslam::yaml {
class Fields;
}

namespace twinslam::bridge {

struct BridgeConfig {
  std::string address = "0.0.0.0";  // interface to listen on ("127.0.0.1": this host only)
  int port = 8765;                   // TCP port of the WebSocket server (Foxglove's default); 0: any free port
  int max_queued = 2000;             // Message Data frames queued per client before the oldest are dropped
  std::string web_root;              // the web view's files (index.html, app.js); empty: the build's (TWINSLAM_WEB_DIR)
  std::string origin;                // "LAT,LON,H" of W (WGS84 [deg, deg, m]): GNSS also drawn in W; empty: not

  // Throws twinslam::InputError "SOURCE: bridge key 'K': what" naming the first bad field.
  void validate(const std::string& source = "BridgeConfig") const;
};

// Binds every key of the YAML form to `config` (one line per field).
void bind_bridge_config(yaml::Fields& fields, BridgeConfig& config);

// YAML text over `base` (`file` only names it in messages); unknown keys and wrong types throw InputError naming the
// file, line and key. Not validated: the caller applies its overrides and calls validate().
BridgeConfig parse_bridge_config(const std::string& text, const std::string& file, const BridgeConfig& base = {});
BridgeConfig load_bridge_config(const std::string& path, const BridgeConfig& base = {});

}  // namespace twinslam::bridge
