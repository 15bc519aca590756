#include "tiles_node.hpp"

#include <spdlog/spdlog.h>

namespace twinslam::tiles {

TilesNode::TilesNode(dds::Node& node, dds::Counters& counters, const TilesConfig& config)
    : node_(node),
      writer_(node.writer<msg::MapTile>(dds::topics::kMapTile)),
      handler_(counters, config, node.config().vehicle_id,
               [this](const msg::MapTile& t) { return writer_.publish(t); }) {
  const TileGrid& grid = handler_.streamer().grid();
  spdlog::info("twin '{}' from {}: {} tiles of {} m, window {} m", grid.twin_id(), config.twin_dir,
               grid.records().size(), grid.tile_size_m(), config.window_m);
  node.subscribe<msg::Odometry>(dds::topics::kOdometry, [this](const msg::Odometry& m) { handler_.on_odometry(m); });
  node.subscribe<msg::GnssFix>(dds::topics::kGnss, [this](const msg::GnssFix& m) { handler_.on_gnss(m); });
  node.subscribe<msg::TileRequest>(dds::topics::kTileRequest,
                                   [this](const msg::TileRequest& m) { handler_.on_request(m); });
}

void wire_idle_inputs(dds::Node& node, dds::Counters& counters) {
  node.subscribe<msg::Odometry>(dds::topics::kOdometry,
                                [&counters](const msg::Odometry&) { counters.add("odometry_in"); });
  node.subscribe<msg::GnssFix>(dds::topics::kGnss, [&counters](const msg::GnssFix&) { counters.add("gnss_in"); });
  node.subscribe<msg::TileRequest>(dds::topics::kTileRequest,
                                   [&counters](const msg::TileRequest&) { counters.add("tile_requests_in"); });
}

TilesNode::~TilesNode() { node_.close_readers(); }

}  // namespace twinslam::tiles
