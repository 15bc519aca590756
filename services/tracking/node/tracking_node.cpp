#include "tracking_node.hpp"

#include "twinslam/dds/convert.hpp"

namespace twinslam::tracking {

TrackingNode::TrackingNode(dds::Node& node, dds::Counters& counters, TrackingNodeOptions options)
    : node_(node),
      counters_(counters),
      handler_(counters, options),
      features_(node.writer<msg::FeatureFrame>(dds::topics::kFeatures)),
      ack_(node.writer<msg::FrameAck>(dds::topics::kFrameAck)),
      worker_(options.imu_wait, [this](const msg::Image& image, std::vector<imu::ImuSample>&& imu) {
        process(image, std::move(imu));
      }) {
  node.subscribe<msg::Imu>(dds::topics::kImu, [this](const msg::Imu& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("imu_in");
    if (!worker_.push_imu({m.stamp_ns(), dds::from_msg(m.gyro_radps()), dds::from_msg(m.accel_mps2())})) {
      counters_.add("imu_rejected");  // not after the previous sample
    }
  });
  node.subscribe<msg::Image>(dds::topics::kImage, [this](const msg::Image& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("images_in");
    worker_.push_frame(std::make_shared<const msg::Image>(m), m.stamp_ns());
  });
}

void TrackingNode::process(const msg::Image& m, std::vector<imu::ImuSample>&& new_imu) {
  if (auto features = handler_.handle(m, std::move(new_imu))) features_.publish(*features);
  send_ack(m);
}

void TrackingNode::send_ack(const msg::Image& m) {
  ack_.publish(dds::frame_ack(m.vehicle_id(), "tracking", m.stamp_ns(), m.seq()));
}

}  // namespace twinslam::tracking
