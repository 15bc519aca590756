#pragma once
// The tracking service's DDS shell: Image + Imu in, FeatureFrame out (and a FrameAck per frame for lockstep replay).
// A frame is processed once the IMU has reached its stamp (so the gyro rotation since the previous frame, used as
// the KLT prediction, is complete), or after `imu_wait` if the IMU stream ends or lags (ImuGatedWorker).
#include <chrono>
#include <vector>

#include "twinslam/camera/camera_config.hpp"
#include "twinslam/core/sensor_worker.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/imu/imu_types.hpp"
#include "twinslam/tracking/frontend.hpp"

namespace twinslam::tracking {

struct TrackingNodeOptions {
  CameraConfig camera;                                   // intrinsics and T_BC (from the dataset's sensor.yaml)
  FrontendConfig frontend;
  std::chrono::milliseconds imu_wait{100};               // how long a frame may wait for IMU past its stamp
};

class TrackingNode {
 public:
  TrackingNode(dds::Node& node, dds::Counters& counters, TrackingNodeOptions options);

 private:
  void process(const msg::Image& image, std::vector<imu::ImuSample>&& new_imu);
  void send_ack(const msg::Image& image);

  dds::Node& node_;
  dds::Counters& counters_;
  TrackingNodeOptions options_;
  Frontend frontend_;
  dds::Writer<msg::FeatureFrame> features_;
  dds::Writer<msg::FrameAck> ack_;
  // Worker-thread state: the IMU since shortly before the previous frame (for the gyro prediction).
  std::vector<imu::ImuSample> imu_;
  std::int64_t last_frame_ns_ = -1;
  unsigned long long seq_ = 0;
  ImuGatedWorker<msg::Image, imu::ImuSample> worker_;  // last: its thread uses the members above
};

}  // namespace twinslam::tracking
