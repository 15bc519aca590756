#pragma once
// The estimator service's DDS shell: FeatureFrame + Imu in, and the global inputs Registration + GnssFix; Odometry per
// frame, LocalMap per keyframe and a FrameAck per processed FeatureFrame (lockstep replay) out. The algorithm is
// SlidingWindowEstimator (twinslam_estimator_core). A frame is processed once the IMU has reached its stamp, or after
// `imu_wait` if the IMU stream ends or lags (the rule of the tracking service): deterministic whenever the IMU covers
// the frame, never stuck at the end of a dataset. Global inputs reach the worker thread through the same
// SensorWorker, in sensor-time order relative to the frames (sensor_worker.hpp), and go to GlobalFusion
// (global_fusion.hpp): GNSS for the initial alignment T_WL (eq. 11), accepted registrations as map factors (eq. 7).
#include <atomic>
#include <chrono>
#include <map>
#include <string>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "twinslam/core/sensor_worker.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/estimator/frame_gap.hpp"
#include "twinslam/estimator/global_fusion.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::estimator {

struct EstimatorNodeOptions {
  SlidingWindowConfig estimator;                  // T_BC, focal_px and imu filled from --camera / --imu
  std::chrono::milliseconds imu_wait{100};        // how long a frame may wait for IMU past its stamp
  GlobalFusionConfig fusion;                      // what to do with GNSS and registrations (off: plain VIO)
  std::optional<InitialPose> initial_pose;        // --initial-pose: T_WL from a user-given start pose
  std::optional<twin::GeoOrigin> origin;          // W's origin (lat, lon, alt): needed to use GNSS fixes
  // Lockstep replay with registration fusion: each LocalMap holds the next frame until the registration answering
  // it arrives (or this long passes), so when a registration is fused does not depend on the edge's speed.
  bool await_registration = false;
  std::chrono::milliseconds registration_wait{10000};
};

// A global measurement on its way to the worker thread, keyed by its sensor stamp (a Registration by the keyframe
// stamp it answers, a GnssFix by its own).
using GlobalInput = std::variant<msg::Registration, msg::GnssFix>;

class EstimatorNode {
 public:
  EstimatorNode(dds::Node& node, dds::Counters& counters, EstimatorNodeOptions options);

 private:
  void handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu, std::vector<GlobalInput>&& global);
  void apply(const GlobalInput& input);
  void process(const msg::FeatureFrame& frame);
  void report_fusion();
  // The ODOM_FAULT_* bits of one frame's estimate (IMU gap, too few features), counted on the heartbeat.
  std::uint32_t frame_faults(const FrameEstimate& e);
  void log_camera_calibration(std::int64_t stamp_ns);

  dds::Node& node_;
  dds::Counters& counters_;
  SlidingWindowEstimator estimator_;  // used by the worker thread only
  GlobalFusion fusion_;               // likewise
  std::unique_ptr<twin::EnuFrame> enu_;  // lat/lon/alt -> W (null without an origin)
  bool await_registration_;
  std::map<std::string, unsigned long long> reported_;  // fusion counts already in the heartbeat
  // ODOM_FAULT_* bits met since the last Odometry: set from DDS callbacks and the worker, taken by the next Odometry.
  std::atomic<std::uint32_t> faults_{0};
  FrameGapDetector frame_gaps_;  // worker thread only
  std::chrono::milliseconds registration_wait_;
  dds::Writer<msg::Odometry> odometry_;
  dds::Writer<msg::LocalMap> local_map_;
  dds::Writer<msg::FrameAck> ack_;

  unsigned long long odom_seq_ = 0, map_seq_ = 0;
  std::int64_t calibration_logged_ns_ = 0;  // stamp of the last log line of the camera rotation calibration
  // Frames are processed once the IMU reaches their stamp, or after imu_wait; global inputs in stamp order with them
  // (see SensorWorker).
  SensorWorker<msg::FeatureFrame, ImuSample, GlobalInput> worker_;  // last: its thread uses the members above
};

}  // namespace twinslam::estimator
