#pragma once
// The registration service's DDS shell. Point-to-plane ICP against the twin (paper eqs. 2-10) plugs in here; until then the node consumes local maps and tiles and publishes no Registration.
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::registration {

// Subscribes the service's inputs and counts them (visible in its heartbeat and in `twinslam topics`).
void wire_registration_inputs(dds::Node& node, dds::Counters& counters);

}  // namespace twinslam::registration
