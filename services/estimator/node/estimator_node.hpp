#pragma once
// The estimator service's DDS shell: FeatureFrame + Imu in; Odometry per frame, LocalMap per keyframe and a FrameAck
// per processed FeatureFrame (lockstep replay) out. The algorithm is SlidingWindowEstimator (twinslam_estimator_core).
// A frame is processed once the IMU has reached its stamp, or after `imu_wait` if the IMU stream ends or lags (the
// rule of the tracking service): deterministic whenever the IMU covers the frame, never stuck at the end of a dataset.
#include <chrono>
#include <vector>

#include "twinslam/core/imu_gated_worker.hpp"
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

 private:
  void handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu);
  void process(const msg::FeatureFrame& frame);

  dds::Node& node_;
  dds::Counters& counters_;
  SlidingWindowEstimator estimator_;  // used by the worker thread only
  dds::Writer<msg::Odometry> odometry_;
  dds::Writer<msg::LocalMap> local_map_;
  dds::Writer<msg::FrameAck> ack_;

  unsigned long long odom_seq_ = 0, map_seq_ = 0;
  // Frames are processed once the IMU reaches their stamp, or after imu_wait (see ImuGatedWorker).
  ImuGatedWorker<msg::FeatureFrame, ImuSample> worker_;  // last: its thread uses the members above
};

}  // namespace twinslam::estimator
