#pragma once
// The estimator service's DDS shell: FeatureFrame + Imu in; Odometry per frame, LocalMap per keyframe and a FrameAck
// per processed FeatureFrame (lockstep replay) out. The algorithm is SlidingWindowEstimator (twinslam_estimator_core).
// A frame is processed once the IMU has reached its stamp, or after `imu_wait` if the IMU stream ends or lags (the
// rule of the tracking service): deterministic whenever the IMU covers the frame, never stuck at the end of a dataset.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"

namespace twinslam::estimator {

struct EstimatorNodeOptions {
  SlidingWindowConfig estimator;                  // T_BC, focal_px and imu filled from --camera / --imu
  std::chrono::milliseconds imu_wait{100};        // how long a frame may wait for IMU past its stamp
};

class EstimatorNode {
 public:
  EstimatorNode(dds::Node& node, dds::Counters& counters, EstimatorNodeOptions options);
  ~EstimatorNode();

 private:
  struct PendingFrame {
    std::shared_ptr<msg::FeatureFrame> frame;
    std::chrono::steady_clock::time_point arrived;
  };
  void worker();
  void process(const msg::FeatureFrame& frame);

  dds::Node& node_;
  dds::Counters& counters_;
  SlidingWindowEstimator estimator_;  // used by the worker thread only
  std::chrono::milliseconds imu_wait_;
  dds::Writer<msg::Odometry> odometry_;
  dds::Writer<msg::LocalMap> local_map_;
  dds::Writer<msg::FrameAck> ack_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<PendingFrame> pending_;
  std::vector<ImuSample> imu_;                    // received, not yet handed to the estimator
  std::int64_t last_imu_ns_ = -1;
  unsigned long long odom_seq_ = 0, map_seq_ = 0;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace twinslam::estimator
