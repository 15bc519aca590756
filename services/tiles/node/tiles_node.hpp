#pragma once
// The tiles service's DDS shell: Odometry, GnssFix and TileRequest in; MapTile out (profile tile.writer: latched,
// one sample per tile). The decisions live in twinslam_tiles_core: VehiclePositions picks the position (aligned
// odometry, else GNSS converted to W at the twin's origin), TileStreamer the tiles each vehicle still needs and which
// of them are not yet on the wire, TileCache their encoded bytes. Heartbeat counters: tiles_sent, bytes_sent,
// tiles_latched (needed by a vehicle but already on the wire), tiles_failed, tiles_over_limit (max_tiles_on_wire
// reached), and the inputs.
#include <mutex>
#include <set>
#include <string>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/tiles/tile_cache.hpp"
#include "twinslam/tiles/tile_streamer.hpp"
#include "twinslam/tiles/tiles_config.hpp"
#include "twinslam/tiles/vehicle_positions.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::tiles {

// `--no-twin`: no store to serve (a EuRoC replay, a dataset whose twin is not a tile store yet). The service only
// counts its inputs, so a deployment that lists it still starts, and says so in its heartbeat (no tiles_sent).
void wire_idle_inputs(dds::Node& node, dds::Counters& counters);

class TilesNode {
 public:
  // Reads the twin index of config.twin_dir (InputError if missing or malformed) and subscribes the inputs. Serves
  // every vehicle when the node's vehicle_id is empty, else only that one.
  TilesNode(dds::Node& node, dds::Counters& counters, const TilesConfig& config);
  ~TilesNode();  // closes the node's readers first: no callback may reach a destroyed member
  TilesNode(const TilesNode&) = delete;
  TilesNode& operator=(const TilesNode&) = delete;

 private:
  bool serves(const std::string& vehicle) const;
  void on_odometry(const msg::Odometry& m);
  void on_gnss(const msg::GnssFix& m);
  void on_request(const msg::TileRequest& m);
  void send(const StreamDecision& d);  // caller holds mutex_
  bool publish_tile(const twin::TileKey& key);

  dds::Node& node_;
  dds::Counters& counters_;
  std::mutex mutex_;  // Fast DDS calls the three readers' callbacks from its own threads
  TileStreamer streamer_;
  VehiclePositions positions_;
  TileCache cache_;
  twin::EnuFrame enu_;  // W at the twin's origin, for GNSS fixes
  dds::Writer<msg::MapTile> writer_;
  std::set<std::string> warned_failed_;  // tiles whose failure was logged
};

}  // namespace twinslam::tiles
