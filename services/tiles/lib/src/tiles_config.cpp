#include "twinslam/tiles/tiles_config.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"

namespace twinslam::tiles {
namespace {

[[noreturn]] void bad(const std::string& file, std::size_t line, const std::string& key, const std::string& what) {
  throw InputError(where(file, line, "tiles key '" + key + "': " + what));
}

std::size_t line_of(const YAML::Node& node) { return static_cast<std::size_t>(node.Mark().line + 1); }

template <class T>
T read(const std::string& file, const std::string& key, const YAML::Node& node, const char* type) {
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    bad(file, line_of(node), key, std::string("expected ") + type);
  }
}

}  // namespace

void TilesConfig::validate(const std::string& source) const {
  // 1 km is far beyond any camera's useful range; a larger window would stream most of a city to each vehicle.
  if (!std::isfinite(window_m) || window_m <= 0.0 || window_m > 1000.0) {
    bad(source, 0, "window_m", "must lie in (0, 1000] m, got " + std::to_string(window_m));
  }
  if (cache_tiles < 1) bad(source, 0, "cache_tiles", "must be >= 1, got " + std::to_string(cache_tiles));
  if (max_tiles_on_wire < 1) {
    bad(source, 0, "max_tiles_on_wire", "must be >= 1, got " + std::to_string(max_tiles_on_wire));
  }
  if (twin_dir.empty()) bad(source, 0, "twin_dir", "must name the twin store directory");
}

TilesConfig parse_tiles_config(const std::string& text, const std::string& file, const TilesConfig& base) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg));
  }
  TilesConfig config = base;
  if (root.IsNull()) return config;
  if (!root.IsMap()) throw InputError(where(file, 0, "expected a YAML mapping of tiles keys"));
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>();
    const YAML::Node& value = item.second;
    if (key == "window_m") {
      config.window_m = read<double>(file, key, value, "a number [m]");
    } else if (key == "cache_tiles") {
      config.cache_tiles = read<int>(file, key, value, "an integer");
    } else if (key == "max_tiles_on_wire") {
      config.max_tiles_on_wire = read<int>(file, key, value, "an integer");
    } else if (key == "twin_dir") {
      config.twin_dir = read<std::string>(file, key, value, "a path");
    } else {
      bad(file, line_of(item.first), key, "unknown key (known: window_m, cache_tiles, twin_dir, max_tiles_on_wire)");
    }
  }
  return config;
}

TilesConfig load_tiles_config(const std::string& path, const TilesConfig& base) {
  std::ifstream in(path);
  if (!in) throw InputError(where(path, 0, "cannot open file"));
  std::stringstream text;
  text << in.rdbuf();
  return parse_tiles_config(text.str(), path, base);
}

}  // namespace twinslam::tiles
