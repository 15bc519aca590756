#pragma once
// The tiles service's one config struct: window around each vehicle, LRU size, where the twin store lives.
// validate() is the one place the values are checked; parse_tiles_config reads the YAML form
//   window_m: 250      # side of the square window around each vehicle [m]
//   cache_tiles: 64    # encoded tiles kept in memory (LRU)
//   twin_dir: /data/twin
//   max_tiles_on_wire: 4096
#include <string>

#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::tiles {

struct TilesConfig {
  // Side of the square window (in E, N) centred on the vehicle [m]: registration's 150 m plus its 50 m prefetch ring
  // on each side (services/registration: tiles are indexed before the vehicle needs them).
  double window_m = 250.0;
  int cache_tiles = 64;     // tiles whose encoded bytes stay in memory (LRU); a re-send needs no disk read
  std::string twin_dir;     // the twin store (`twinslam twin build` output)
  int max_tiles_on_wire = 4096;  // tiles the MapTile writer latches; at most tile.writer's max_instances (QoS XML)

  // Throws twinslam::InputError "SOURCE: tiles key 'K': what" naming the first bad field.
  void validate(const std::string& source = "TilesConfig") const;
};

// Binds every key of the YAML form to `config` (one line per field).
void bind_tiles_config(yaml::Fields& fields, TilesConfig& config);

// Parses YAML text (`file` only names it in messages) over `base`; unknown keys and wrong types throw InputError
// naming the file, line and key. Not validated: the caller applies its overrides (e.g. --twin) and calls validate().
TilesConfig parse_tiles_config(const std::string& text, const std::string& file, const TilesConfig& base = {});
TilesConfig load_tiles_config(const std::string& path, const TilesConfig& base = {});

}  // namespace twinslam::tiles
