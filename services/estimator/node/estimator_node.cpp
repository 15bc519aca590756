#include "estimator_node.hpp"

#include "twinslam/dds/convert.hpp"

namespace twinslam::estimator {

EstimatorNode::EstimatorNode(dds::Node& node, dds::Counters& counters, EstimatorNodeOptions options)
    : node_(node),
      counters_(counters),
      handler_(counters, options),
      await_registration_(options.await_registration),
      registration_wait_(options.registration_wait),
      odometry_(node.writer<msg::Odometry>(dds::topics::kOdometry)),
      local_map_(node.writer<msg::LocalMap>(dds::topics::kLocalMap)),
      ack_(node.writer<msg::FrameAck>(dds::topics::kFrameAck)),
      worker_(options.imu_wait,
              [this](const msg::FeatureFrame& frame, std::vector<ImuSample>&& imu, std::vector<GlobalInput>&& global) {
                handle(frame, std::move(imu), std::move(global));
              }) {
  node.subscribe<msg::Imu>(dds::topics::kImu, [this](const msg::Imu& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("imu_in");
    if (!worker_.push_imu({m.stamp_ns(), dds::from_msg(m.gyro_radps()), dds::from_msg(m.accel_mps2())})) {
      counters_.add("imu_rejected");  // duplicate or out of order: the estimator needs increasing stamps
      handler_.note_fault(msg::ODOM_FAULT_IMU_REJECTED);
    }
  });
  node.subscribe<msg::FeatureFrame>(dds::topics::kFeatures, [this](const msg::FeatureFrame& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("features_in");
    worker_.push_frame(std::make_shared<const msg::FeatureFrame>(m), m.stamp_ns());
  });
  node.subscribe<msg::Registration>(dds::topics::kRegistration, [this](const msg::Registration& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    worker_.push_side(m.keyframe_stamp_ns(), m);
  });
  node.subscribe<msg::GnssFix>(dds::topics::kGnss, [this](const msg::GnssFix& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    worker_.push_side(m.stamp_ns(), m);
  });
}

void EstimatorNode::handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu,
                           std::vector<GlobalInput>&& global) {
  const EstimatorHandler::Output out = handler_.handle(frame, std::move(new_imu), std::move(global));
  if (out.odometry) odometry_.publish(*out.odometry);
  if (out.local_map) {
    local_map_.publish(*out.local_map);
    if (await_registration_) worker_.expect_side(out.local_map->keyframe_stamp_ns(), registration_wait_);
  }
  if (const unsigned long long timeouts = worker_.expectations_timed_out(); timeouts > wait_timeouts_reported_) {
    counters_.add("registration_wait_timeouts", timeouts - wait_timeouts_reported_);
    wait_timeouts_reported_ = timeouts;
  }
  ack_.publish(dds::frame_ack(frame.vehicle_id(), "estimator", frame.stamp_ns(), frame.seq()));
}

}  // namespace twinslam::estimator
