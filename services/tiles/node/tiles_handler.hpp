#pragma once
// The tiles service's message handlers without its topics (tiles_node.cpp wires them): Odometry, GnssFix and
// TileRequest in, MapTiles out through `publish`. The decisions live in twinslam_tiles_core: VehiclePositions picks
// the position (aligned odometry, else GNSS converted to W at the twin's origin), TileStreamer the tiles each vehicle
// still needs and which of them are not yet on the wire, TileCache their encoded bytes. No sample makes a handler
// throw (a Fast DDS listener thread would die): a NaN or far-away position, a window of any size, unknown tile keys
// are counted and refused (fed arbitrary samples by tests/fuzz/targets/dds_tiles.cpp). Heartbeat counters:
// tiles_sent, bytes_sent, tiles_latched (needed by a vehicle but already on the wire), tiles_failed,
// tiles_over_limit (max_tiles_on_wire reached), the inputs and their rejections.
#include <functional>
#include <mutex>
#include <set>
#include <string>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/tiles/tile_cache.hpp"
#include "twinslam/tiles/tile_streamer.hpp"
#include "twinslam/tiles/tiles_config.hpp"
#include "twinslam/tiles/vehicle_positions.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::tiles {

class TilesHandler {
 public:
  using Publish = std::function<bool(const msg::MapTile&)>;  // false: the tile did not go out

  // Reads the twin index of config.twin_dir (InputError if missing or malformed). Serves every vehicle when
  // `vehicle_id` is empty, else only that one.
  TilesHandler(dds::Counters& counters, const TilesConfig& config, std::string vehicle_id, Publish publish);

  // Thread-safe: each may be called from any reader's thread.
  void on_odometry(const msg::Odometry& m);
  void on_gnss(const msg::GnssFix& m);
  void on_request(const msg::TileRequest& m);

  const TileStreamer& streamer() const { return streamer_; }

 private:
  bool serves(const std::string& vehicle) const { return vehicle_id_.empty() || vehicle == vehicle_id_; }
  void send(const StreamDecision& d);  // caller holds mutex_
  bool publish_tile(const twin::TileKey& key);

  dds::Counters& counters_;
  const std::string vehicle_id_;
  const Publish publish_;
  std::mutex mutex_;
  TileStreamer streamer_;
  VehiclePositions positions_;
  TileCache cache_;
  twin::EnuFrame enu_;  // W at the twin's origin, for GNSS fixes
  std::set<std::string> warned_failed_;  // tiles whose failure was logged
};

}  // namespace twinslam::tiles
