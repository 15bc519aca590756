#pragma once
// The registration service's DDS shell (paper Sec. III-C on an edge server): LocalMap (every vehicle's landmark
// cloud per keyframe) and MapTile (the twin, latched) in; Registration out, keyed by vehicle. One worker thread
// serves the vehicles in turn; for each it keeps only the newest LocalMap not yet registered (a slower edge skips
// clouds instead of queueing them: `skipped` in the heartbeat), so the estimator is never held up by it. Tiles are
// decoded and indexed on the worker when they enter a vehicle's window (WindowedTwin). The algorithm is
// register_cloud() of twinslam_registration_core.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/registration/persistence_gate.hpp"
#include "twinslam/registration/registration.hpp"
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
};

// Wire key "<twin id>/<ix>_<iy>" -> tile key; nullopt if malformed.
std::optional<twin::TileKey> parse_tile_key(const std::string& wire_key);
// Library status -> message status.
msg::RegistrationStatus to_msg(RegistrationStatus status);

class RegistrationNode {
 public:
  RegistrationNode(dds::Node& node, dds::Counters& counters, const RegistrationNodeOptions& options);
  ~RegistrationNode();
  RegistrationNode(const RegistrationNode&) = delete;
  RegistrationNode& operator=(const RegistrationNode&) = delete;

 private:
  struct Pending {
    std::shared_ptr<const msg::LocalMap> map;
    std::chrono::steady_clock::time_point arrived;
  };
  void run();
  void serve(const Pending& p);
  // faults.correction_offset (registration_config.hpp): moves an accepted correction east when its keyframe is due.
  void inject_fault(const msg::LocalMap& m, RegistrationResult& r);

  dds::Node& node_;
  dds::Counters& counters_;
  RegistrationNodeOptions options_;
  dds::Writer<msg::Registration> writer_;
  WindowedTwin twin_;  // worker only
  std::map<std::string, PersistenceGate> persistence_;  // per vehicle, worker only
  std::map<std::string, std::int64_t> first_stamp_ns_;  // per vehicle, worker only: its first LocalMap (faults)
  unsigned long long seq_ = 0;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, Pending> pending_;               // newest LocalMap per vehicle
  std::deque<std::shared_ptr<const msg::MapTile>> tiles_in_;
  std::string last_served_;                              // round robin over vehicles
  bool stop_ = false;
  std::thread worker_;  // last
};

}  // namespace twinslam::registration
