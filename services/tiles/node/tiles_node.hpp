#pragma once
// The tiles service's DDS shell. The tiled twin store and streaming logic (issue 7) plug in here; until then the node follows its inputs (odometry, GNSS, tile requests) and publishes no tiles.
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::tiles {

// Subscribes the service's inputs and counts them (visible in its heartbeat and in `twinslam topics`).
void wire_tiles_inputs(dds::Node& node, dds::Counters& counters);

}  // namespace twinslam::tiles
