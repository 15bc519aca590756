#include "estimator_node.hpp"

#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"

namespace twinslam::estimator {
namespace {
using dds::to_msg;  // Eigen -> message, next to the status overload below

msg::OdometryStatus to_msg(EstimatorStatus s) {
  switch (s) {
    case EstimatorStatus::kTracking: return msg::ODOM_TRACKING;
    case EstimatorStatus::kReinitializing: return msg::ODOM_REINITIALIZING;
    case EstimatorStatus::kInitializing: break;
  }
  return msg::ODOM_INITIALIZING;
}

}  // namespace

EstimatorNode::EstimatorNode(dds::Node& node, dds::Counters& counters, EstimatorNodeOptions options)
    : node_(node),
      counters_(counters),
      estimator_(options.estimator),
      odometry_(node.writer<msg::Odometry>(dds::topics::kOdometry)),
      local_map_(node.writer<msg::LocalMap>(dds::topics::kLocalMap)),
      ack_(node.writer<msg::FrameAck>(dds::topics::kFrameAck)),
      worker_(options.imu_wait, [this](const msg::FeatureFrame& frame, std::vector<ImuSample>&& imu) {
        handle(frame, std::move(imu));
      }) {
  node.subscribe<msg::Imu>(dds::topics::kImu, [this](const msg::Imu& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("imu_in");
    if (!worker_.push_imu({m.stamp_ns(), dds::from_msg(m.gyro_radps()), dds::from_msg(m.accel_mps2())})) {
      counters_.add("imu_rejected");  // duplicate or out of order: the estimator needs increasing stamps
    }
  });
  node.subscribe<msg::FeatureFrame>(dds::topics::kFeatures, [this](const msg::FeatureFrame& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("features_in");
    worker_.push_frame(std::make_shared<const msg::FeatureFrame>(m), m.stamp_ns());
  });
}

void EstimatorNode::handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu) {
  for (const auto& s : new_imu) {
    try {
      estimator_.add_imu(s);
    } catch (const InputError& e) {
      counters_.add("imu_rejected");
      spdlog::warn("imu: {}", e.what());
    }
  }
  process(frame);
}

void EstimatorNode::process(const msg::FeatureFrame& m) {
  std::vector<FeatureBearing> features;
  features.reserve(m.features().size());
  for (const auto& f : m.features()) {
    const Eigen::Vector3d b(f.bearing_C().x(), f.bearing_C().y(), f.bearing_C().z());
    if (b.allFinite() && b.norm() > 0.5) features.push_back({static_cast<std::int64_t>(f.id()), b.normalized()});
  }
  try {
    const FrameEstimate e = estimator_.add_frame(m.stamp_ns(), features);
    msg::Odometry odom;
    odom.vehicle_id(m.vehicle_id());
    odom.stamp_ns(m.stamp_ns());
    odom.seq(odom_seq_++);
    odom.status(to_msg(e.status));
    odom.T_LB(to_msg(e.T_LB));
    odom.T_WL(to_msg(Eigen::Isometry3d::Identity()));  // aligned by a later issue (registration / GNSS)
    odom.T_WB(to_msg(e.T_LB));
    odom.v_L(to_msg(e.v_L));
    odom.bias_gyro(to_msg(e.bias.gyro));
    odom.bias_accel(to_msg(e.bias.accel));
    odom.estimator_ms(e.estimator_ms);
    odometry_.publish(odom);
    counters_.add("odometry_out");
    if (e.init_timed_out && counters_.get("init_timeout_reported") == 0) {
      counters_.add("init_timeout_reported");
      spdlog::warn("neither rest nor a motion initialization succeeded within init_timeout_s");
    }
    if (const auto& map = estimator_.local_map()) {
      msg::LocalMap lm;
      lm.vehicle_id(m.vehicle_id());
      lm.keyframe_stamp_ns(map->keyframe_stamp_ns);
      lm.seq(map_seq_++);
      lm.T_LB(to_msg(map->T_LB));
      lm.T_WL(to_msg(Eigen::Isometry3d::Identity()));
      lm.landmarks().reserve(map->landmarks.size());
      for (const auto& l : map->landmarks) {
        msg::Landmark ml;
        ml.id(static_cast<unsigned long long>(l.id));
        ml.p_L(to_msg(l.p_L));
        ml.quality(static_cast<float>(l.quality));
        lm.landmarks().push_back(ml);
      }
      local_map_.publish(lm);
      counters_.add("local_maps_out");
    }
  } catch (const InputError& e) {
    counters_.add("frames_rejected");
    spdlog::warn("feature frame {}: {}", m.stamp_ns(), e.what());
  } catch (const std::exception& e) {
    // An internal failure on one frame must not stop the service (nor lockstep replay, which waits for the ack).
    counters_.add("frames_failed");
    spdlog::error("feature frame {}: estimator failed: {}", m.stamp_ns(), e.what());
  }
  ack_.publish(dds::frame_ack(m.vehicle_id(), "estimator", m.stamp_ns(), m.seq()));
}

}  // namespace twinslam::estimator
