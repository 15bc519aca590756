#include "tiles_node.hpp"

namespace twinslam::tiles {

void wire_tiles_inputs(dds::Node& node, dds::Counters& counters) {
  node.subscribe<msg::Odometry>(dds::topics::kOdometry, [&counters](const msg::Odometry&) { counters.add("odometry_in"); });
  node.subscribe<msg::GnssFix>(dds::topics::kGnss, [&counters](const msg::GnssFix&) { counters.add("gnss_in"); });
  node.subscribe<msg::TileRequest>(dds::topics::kTileRequest, [&counters](const msg::TileRequest&) { counters.add("tile_requests_in"); });
}

}  // namespace twinslam::tiles
