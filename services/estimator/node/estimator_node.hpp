#pragma once
// The estimator service's DDS shell: FeatureFrame + Imu in, and the global inputs Registration + GnssFix; Odometry per
// frame, LocalMap per keyframe and a FrameAck per processed FeatureFrame (lockstep replay) out. The algorithm is
// SlidingWindowEstimator (twinslam_estimator_core). A frame is processed once the IMU has reached its stamp, or after
// `imu_wait` if the IMU stream ends or lags (the rule of the tracking service): deterministic whenever the IMU covers
// the frame, never stuck at the end of a dataset. Global inputs reach the worker thread through the same
// SensorWorker, in sensor-time order relative to the frames (sensor_worker.hpp). What the samples become is
// EstimatorHandler's (estimator_handler.hpp, free of DDS): GlobalFusion (global_fusion.hpp) takes GNSS for the initial
// alignment T_WL (eq. 11) and accepted registrations as map factors (eq. 7).
#include <atomic>
#include <chrono>
#include <map>
#include <string>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "estimator_handler.hpp"
#include "registration_wait.hpp"
#include "twinslam/core/sensor_worker.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::estimator {

class EstimatorNode {
 public:
  EstimatorNode(dds::Node& node, dds::Counters& counters, EstimatorNodeOptions options);

  // True once a registration service can answer: the LocalMap writer has a matched reader and the Registration reader
  // a matched writer. Under DDS-Security each pair of processes authenticates on its own, so the run seeing every
  // service ready does not mean the estimator and the registration see each other yet.
  bool registration_link_up() const;
  // Blocks until registration_link_up() or `timeout` passes (or shutdown); returns registration_link_up().
  bool wait_for_registration_link(std::chrono::milliseconds timeout) const;

 private:
  void handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu, std::vector<GlobalInput>&& global);
  // Per frame (worker thread): counts the waits for a registration that ran out, and says when it gives up waiting.
  void count_registration_waits();

  dds::Node& node_;
  dds::Counters& counters_;
  EstimatorHandler handler_;  // the worker thread's (note_fault from any thread)
  bool await_registration_;
  std::chrono::milliseconds registration_wait_;
  RegistrationWait registration_wait_policy_;  // worker thread only
  std::atomic<unsigned long long> registrations_in_{0};  // counted on the reader's thread
  const dds::ReaderStatus* registration_status_ = nullptr;  // set before frames can arrive
  dds::Writer<msg::Odometry> odometry_;
  dds::Writer<msg::LocalMap> local_map_;
  dds::Writer<msg::FrameAck> ack_;
  // Frames are processed once the IMU reaches their stamp, or after imu_wait; global inputs in stamp order with them
  // (see SensorWorker).
  SensorWorker<msg::FeatureFrame, ImuSample, GlobalInput> worker_;  // last: its thread uses the members above
};

}  // namespace twinslam::estimator
