#pragma once
// The tracking service's DDS shell. Subscribes Image and Imu. The frontend algorithm (detection, IMU-aided KLT,
// RANSAC) arrives with the tracking issue; until then the node consumes and counts its inputs, publishes no
// FeatureFrame (it has none to give), and in lockstep acknowledges each image it has consumed so replay proceeds.
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::tracking {

class TrackingNode {
 public:
  TrackingNode(dds::Node& node, dds::Counters& counters);

 private:
  dds::Node& node_;
  dds::Counters& counters_;
  dds::Writer<msg::FrameAck> ack_;
};

}  // namespace twinslam::tracking
