#pragma once
// The tracking service's DDS shell: Image + Imu in, FeatureFrame out (and a FrameAck per frame for lockstep replay).
// A frame is processed once the IMU has reached its stamp (so the gyro rotation since the previous frame, used as
// the KLT prediction, is complete), or after `imu_wait` if the IMU stream ends or lags (ImuGatedWorker); the frame
// itself is TrackingHandler's (tracking_handler.hpp).
#include <vector>

#include "tracking_handler.hpp"
#include "twinslam/core/sensor_worker.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/imu/imu_types.hpp"

namespace twinslam::tracking {

class TrackingNode {
 public:
  TrackingNode(dds::Node& node, dds::Counters& counters, TrackingNodeOptions options);

 private:
  void process(const msg::Image& image, std::vector<imu::ImuSample>&& new_imu);
  void send_ack(const msg::Image& image);

  dds::Node& node_;
  dds::Counters& counters_;
  TrackingHandler handler_;  // worker-thread state
  dds::Writer<msg::FeatureFrame> features_;
  dds::Writer<msg::FrameAck> ack_;
  ImuGatedWorker<msg::Image, imu::ImuSample> worker_;  // last: its thread uses the members above
};

}  // namespace twinslam::tracking
