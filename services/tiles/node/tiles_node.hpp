#pragma once
// The tiles service's DDS shell: Odometry, GnssFix and TileRequest in; MapTile out (profile tile.writer: latched,
// one sample per tile). What each message does is tiles_handler.hpp's.
#include "tiles_handler.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

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
  dds::Node& node_;
  dds::Writer<msg::MapTile> writer_;
  TilesHandler handler_;
};

}  // namespace twinslam::tiles
