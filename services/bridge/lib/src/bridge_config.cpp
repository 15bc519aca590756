#include "twinslam/bridge/bridge_config.hpp"

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::bridge {

void BridgeConfig::validate(const std::string& source) const {
  auto bad = [&](const std::string& key, const std::string& what) {
    throw InputError(where(source, 0, "bridge key '" + key + "': " + what));
  };
  if (address.empty()) bad("address", "must name an interface, e.g. 0.0.0.0");
  if (port < 0 || port > 65535) bad("port", "must lie in [0, 65535], got " + std::to_string(port));
  if (max_queued < 2) bad("max_queued", "must be >= 2, got " + std::to_string(max_queued));
}

void bind_bridge_config(yaml::Fields& fields, BridgeConfig& config) {
  fields.text("address", config.address, "an interface address")
      .integer("port", config.port)
      .integer("max_queued", config.max_queued)
      .text("web_root", config.web_root, "a directory")
      .text("origin", config.origin, "\"LAT,LON,H\"");
}

BridgeConfig parse_bridge_config(const std::string& text, const std::string& file, const BridgeConfig& base) {
  BridgeConfig config = base;
  yaml::Fields fields("bridge");
  bind_bridge_config(fields, config);
  fields.parse(text, file);
  return config;
}

BridgeConfig load_bridge_config(const std::string& path, const BridgeConfig& base) {
  return parse_bridge_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::bridge
