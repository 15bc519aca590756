#include "estimator_node.hpp"

#include <spdlog/spdlog.h>

#include <thread>

#include "twinslam/core/shutdown.hpp"
#include "twinslam/dds/convert.hpp"

namespace twinslam::estimator {

EstimatorNode::EstimatorNode(dds::Node& node, dds::Counters& counters, EstimatorNodeOptions options)
    : node_(node),
      counters_(counters),
      handler_(counters, options),
      await_registration_(options.await_registration),
      registration_wait_(options.registration_wait),
      registration_wait_policy_(options.registration_give_up_after),
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
  // Before the frame reader: handle() (on a frame) reads registration_status_.
  registration_status_ =
      &node.subscribe<msg::Registration>(dds::topics::kRegistration, [this](const msg::Registration& m) {
        if (m.vehicle_id() != node_.config().vehicle_id) return;
        registrations_in_.fetch_add(1);
        worker_.push_side(m.keyframe_stamp_ns(), m);
      });
  node.subscribe<msg::FeatureFrame>(dds::topics::kFeatures, [this](const msg::FeatureFrame& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("features_in");
    worker_.push_frame(std::make_shared<const msg::FeatureFrame>(m), m.stamp_ns());
  });
  node.subscribe<msg::GnssFix>(dds::topics::kGnss, [this](const msg::GnssFix& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    worker_.push_side(m.stamp_ns(), m);
  });
}

void EstimatorNode::handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu,
                           std::vector<GlobalInput>&& global) {
  const EstimatorHandler::Output out = handler_.handle(frame, std::move(new_imu), std::move(global));
  if (await_registration_) count_registration_waits();
  if (out.odometry) odometry_.publish(*out.odometry);
  if (out.local_map) {
    local_map_.publish(*out.local_map);
    // The link is queried only here, once per keyframe: it asks Fast DDS for the matched endpoints.
    if (await_registration_ && registration_wait_policy_.should_wait(registration_link_up())) {
      worker_.expect_side(out.local_map->keyframe_stamp_ns(), registration_wait_);
    }
  }
  ack_.publish(dds::frame_ack(frame.vehicle_id(), "estimator", frame.stamp_ns(), frame.seq()));
}

void EstimatorNode::count_registration_waits() {
  const RegistrationWait::Update u = registration_wait_policy_.observe(worker_.expectations_timed_out(),
                                                                       registrations_in_.load());
  if (u.timed_out > 0) counters_.add("registration_wait_timeouts", u.timed_out);
  if (u.gave_up) {
    counters_.add("registration_wait_suspended");
    spdlog::warn("the registration did not answer the last LocalMaps in time: frames no longer wait for it until a "
                 "registration arrives");
  }
}

bool EstimatorNode::registration_link_up() const {
  return registration_status_->matched_writers.load() > 0 && local_map_.matched_readers() > 0;
}

bool EstimatorNode::wait_for_registration_link(std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!registration_link_up() && !shutdown_requested() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return registration_link_up();
}

}  // namespace twinslam::estimator
