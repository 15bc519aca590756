#pragma once
// The registration service's message handlers without its threads and topics (registration_node.hpp wires them): a
// MapTile goes into the windowed twin, a LocalMap comes back as its Registration. No sample makes them throw or
// publish something unusable: bad input becomes a rejection whose reason says what was wrong (fuzzed by
// tests/fuzz/targets/dds_registration.cpp, fed arbitrary samples).
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/registration/persistence_gate.hpp"
#include "twinslam/registration/registration.hpp"
#include "twinslam/registration/scale_tracker.hpp"
#include "twinslam/registration/windowed_twin.hpp"

namespace twinslam::registration {

struct RegistrationNodeOptions {
  RegistrationConfig registration;
  double tile_size_m = 50.0;       // side of the twin store's tiles (`twinslam twin build --tile-size`) [m]
  double window_m = 150.0;         // square window of twin around each vehicle (the paper's 150 m) [m]
  std::size_t max_stored_tiles = 4096;  // compressed tiles kept (farthest evicted first)
  double prefetch_m = 50.0;             // ring around the window indexed ahead (windowed_twin.hpp) [m]
  std::size_t prefetch_per_update = 1;  // ring tiles built per registration at most
  double keep_m = 50.0;                 // indexed tiles are dropped beyond the ring plus this (hysteresis) [m]
  // A LocalMap with more landmarks is refused unread: the estimator sends a few hundred (its window and horizon), and
  // a million would hold the one worker for seconds while every other vehicle waits.
  std::size_t max_landmarks = 100000;
};

// Wire key "<twin id>/<ix>_<iy>" -> tile key; nullopt if malformed.
std::optional<twin::TileKey> parse_tile_key(const std::string& wire_key);
// Library status -> message status.
msg::RegistrationStatus to_msg(RegistrationStatus status);

class RegistrationHandler {
 public:
  RegistrationHandler(dds::Counters& counters, const RegistrationNodeOptions& options);

  // A twin tile from the tiles service (a malformed key is counted and logged; its Draco bytes are decoded only when
  // the tile enters a vehicle's window).
  void on_tile(const msg::MapTile& tile);
  // The Registration answering a LocalMap, everything but latency_ms (the node's clock) filled in.
  msg::Registration on_local_map(const msg::LocalMap& map);

 private:
  // The registration itself (throws InputError for a cloud that cannot be registered at all).
  void register_map(const msg::LocalMap& m, msg::Registration& out);
  // faults.correction_offset (registration_config.hpp): moves an accepted correction east when its keyframe is due.
  void inject_fault(const msg::LocalMap& m, RegistrationResult& r);

  dds::Counters& counters_;
  RegistrationNodeOptions options_;
  WindowedTwin twin_;
  std::map<std::string, PersistenceGate> persistence_;  // per vehicle
  std::map<std::string, ScaleTracker> scale_;           // per vehicle
  std::map<std::string, std::int64_t> first_stamp_ns_;  // per vehicle: its first LocalMap served (faults)
  unsigned long long seq_ = 0;
};

}  // namespace twinslam::registration
