#include "tracking_node.hpp"

namespace twinslam::tracking {

TrackingNode::TrackingNode(dds::Node& node, dds::Counters& counters)
    : node_(node), counters_(counters), ack_(node.writer<msg::FrameAck>(dds::topics::kFrameAck)) {
  node.subscribe<msg::Imu>(dds::topics::kImu, [this](const msg::Imu& m) {
    if (m.vehicle_id() == node_.config().vehicle_id) counters_.add("imu_in");
  });
  node.subscribe<msg::Image>(dds::topics::kImage, [this](const msg::Image& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("images_in");
    msg::FrameAck ack;
    ack.vehicle_id(m.vehicle_id());
    ack.service("tracking");
    ack.stamp_ns(m.stamp_ns());
    ack.seq(m.seq());
    ack_.publish(ack);
  });
}

}  // namespace twinslam::tracking
