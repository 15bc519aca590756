#pragma once
// The estimator service's DDS shell. The sliding-window estimator (issue 5) plugs in here; until it exists the node consumes FeatureFrame and Imu and publishes no Odometry or LocalMap, since it has none to give.
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::estimator {

// Subscribes the service's inputs and counts them (visible in its heartbeat and in `twinslam topics`).
void wire_estimator_inputs(dds::Node& node, dds::Counters& counters);

}  // namespace twinslam::estimator
