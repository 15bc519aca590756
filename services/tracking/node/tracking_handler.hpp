#pragma once
// The tracking service's frame handler without its threads and topics (tracking_node.hpp wires them): one Image and
// the IMU samples that arrived since the previous frame become the frame's FeatureFrame. No sample makes it throw:
// an image that does not match the camera, or whose stamp the frontend refuses, is skipped and counted
// (images_rejected) (fuzzed by tests/fuzz/targets/dds_tracking.cpp, fed arbitrary samples).
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "twinslam/camera/camera_config.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/imu/imu_types.hpp"
#include "twinslam/tracking/frontend.hpp"

namespace twinslam::tracking {

struct TrackingNodeOptions {
  CameraConfig camera;                                   // intrinsics and T_BC (from the dataset's sensor.yaml)
  FrontendConfig frontend;
  std::chrono::milliseconds imu_wait{100};               // how long a frame may wait for IMU past its stamp
};

class TrackingHandler {
 public:
  TrackingHandler(dds::Counters& counters, const TrackingNodeOptions& options);

  // One frame with the IMU samples since the previous one, in stamp order (ImuGatedWorker). Returns the features to
  // publish, or nothing for a skipped frame (the frame is acknowledged either way).
  std::optional<msg::FeatureFrame> handle(const msg::Image& image, std::vector<imu::ImuSample>&& new_imu);

 private:
  bool matches_camera(const msg::Image& m) const;

  dds::Counters& counters_;
  TrackingNodeOptions options_;
  Frontend frontend_;
  // The IMU since shortly before the previous frame (for the gyro prediction).
  std::vector<imu::ImuSample> imu_;
  std::int64_t last_frame_ns_ = -1;
  unsigned long long seq_ = 0;
};

}  // namespace twinslam::tracking
