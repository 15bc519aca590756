#include "twinslam/tiles/tiles_config.hpp"

#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::tiles {
namespace {

[[noreturn]] void bad(const std::string& file, const std::string& key, const std::string& what) {
  throw InputError(where(file, 0, "tiles key '" + key + "': " + what));
}

}  // namespace

void TilesConfig::validate(const std::string& source) const {
  // 1 km is far beyond any camera's useful range; a larger window would stream most of a city to each vehicle.
  if (!std::isfinite(window_m) || window_m <= 0.0 || window_m > 1000.0) {
    bad(source, "window_m", "must lie in (0, 1000] m, got " + std::to_string(window_m));
  }
  if (cache_tiles < 1) bad(source, "cache_tiles", "must be >= 1, got " + std::to_string(cache_tiles));
  if (max_tiles_on_wire < 1) {
    bad(source, "max_tiles_on_wire", "must be >= 1, got " + std::to_string(max_tiles_on_wire));
  }
  if (twin_dir.empty()) bad(source, "twin_dir", "must name the twin store directory");
}

void bind_tiles_config(yaml::Fields& fields, TilesConfig& config) {
  fields.number("window_m", config.window_m, "m")
      .integer("cache_tiles", config.cache_tiles)
      .text("twin_dir", config.twin_dir, "a path")
      .integer("max_tiles_on_wire", config.max_tiles_on_wire);
}

TilesConfig parse_tiles_config(const std::string& text, const std::string& file, const TilesConfig& base) {
  TilesConfig config = base;
  yaml::Fields fields("tiles");
  bind_tiles_config(fields, config);
  fields.parse(text, file);
  return config;
}

TilesConfig load_tiles_config(const std::string& path, const TilesConfig& base) {
  return parse_tiles_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::tiles
