#pragma once
// Which Foxglove channels a pipeline message feeds, and their messages (well_known.hpp): per vehicle V
//   /V/estimate/pose        foxglove.PoseInFrame     every Odometry (T_WB)
//   /V/estimate/path        foxglove.PosesInFrame    the path so far, each time it grew by `path_spacing_m`
//   /V/gnss                 foxglove.LocationFix     every GnssFix (Foxglove's Map panel)
//   /V/landmarks            foxglove.PointCloud      every LocalMap, placed by the estimator (T_WL)
//   /V/landmarks/registered foxglove.PointCloud      the same landmarks after an accepted registration (eq. 3)
//   /V/registration         twinslam.RegistrationHealth  every Registration
// and for all vehicles /twin/tiles (foxglove.SceneUpdate, one entity per MapTile, latched by tile key: a viewer that
// comes late needs every tile). Thread-safe (DDS listeners call it concurrently); never throws: a tile whose mesh
// does not decode gives no message and is counted (tiles_undecodable).
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "twinslam/foxglove/well_known.hpp"

namespace twinslam::foxglove {

struct DerivedMessage {
  std::string topic;
  const Schema* schema = nullptr;
  std::string json;
  // Set: a late subscriber gets the last message of each key on this topic (any string, empty included).
  std::optional<std::string> latch_key;
};

struct DerivedChannelsConfig {
  double path_spacing_m = 1.0;     // a pose joins the path once this far from the last one [m]
  std::size_t max_path_poses = 4000;  // past it, every other pose of the path is dropped (the path keeps its extent)
  std::size_t kept_local_maps = 16;   // per vehicle, for the registered cloud (a registration answers a recent one)
};

class DerivedChannels {
 public:
  explicit DerivedChannels(DerivedChannelsConfig config = {}) : config_(config) {}

  // render = false (nobody watches): only the state is kept up to date (the path, the held LocalMaps) and only the
  // latched messages (tiles) are made; no JSON is built for anything else.
  std::vector<DerivedMessage> on(const msg::Odometry& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::GnssFix& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::LocalMap& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::Registration& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::MapTile& m, bool render = true);
  template <class T>
  std::vector<DerivedMessage> on(const T&, bool = true) {
    return {};  // no well-known form (sensor streams, heartbeats: their CDR channels carry them)
  }

  std::uint64_t tiles_undecodable() const;
  // "/V" for a vehicle id ("/unnamed" for an empty one).
  static std::string prefix(const std::string& vehicle_id);

 private:
  struct Vehicle {
    std::vector<PoseW> path;
    std::deque<msg::LocalMap> local_maps;
  };
  DerivedChannelsConfig config_;
  mutable std::mutex mutex_;
  std::map<std::string, Vehicle> vehicles_;
  std::uint64_t tiles_undecodable_ = 0;
};

}  // namespace twinslam::foxglove
