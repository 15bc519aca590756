#pragma once
// The estimator service's message handlers without its threads and topics (estimator_node.hpp wires them): the
// IMU samples, global inputs (Registration, GnssFix) and one FeatureFrame the worker hands over become the frame's
// Odometry and, for a keyframe, its LocalMap. No sample makes them throw: bad input is refused, counted on the
// heartbeat and reported in Odometry.faults (fuzzed by tests/fuzz/targets/dds_estimator.cpp, fed arbitrary samples).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/estimator/frame_gap.hpp"
#include "twinslam/estimator/global_fusion.hpp"
#include "twinslam/estimator/resume.hpp"
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
  // At start the estimator announces ready only once the registration can answer (or this long passed): frames are
  // never held for a service that cannot hear the LocalMaps. After this many waits in a row run out, frames stop
  // waiting until a registration arrives again: a hung edge costs a few waits, not registration_wait per keyframe.
  std::chrono::milliseconds registration_link_wait{30000};
  int registration_give_up_after = 3;
  // --checkpoint FILE: the newest state in W written there every checkpoint_every_s of sensor time once the alignment
  // is declared, and resumed from at start when fresh enough (resume.hpp). Empty: neither.
  std::string checkpoint_path;
  double checkpoint_every_s = 0.5;  // [s] of sensor time
  ResumeConfig resume;
};

// A global measurement on its way to the worker thread, keyed by its sensor stamp (a Registration by the keyframe
// stamp it answers, a GnssFix by its own).
using GlobalInput = std::variant<msg::Registration, msg::GnssFix>;

class EstimatorHandler {
 public:
  EstimatorHandler(dds::Counters& counters, const EstimatorNodeOptions& options);

  struct Output {
    std::optional<msg::Odometry> odometry;  // none when the estimator failed on the frame (counted frames_failed)
    std::optional<msg::LocalMap> local_map;  // a keyframe's
  };
  // One frame with the IMU samples and global inputs that precede it, in sensor-time order (SensorWorker).
  Output handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu, std::vector<GlobalInput>&& global);
  // A fault met outside handle() (an IMU sample the worker refused): reported by the next Odometry. Thread-safe.
  void note_fault(std::uint32_t odom_fault_bit) { faults_.fetch_or(odom_fault_bit); }

 private:
  void apply(const GlobalInput& input);
  Output process(const msg::FeatureFrame& frame);
  msg::LocalMap local_map_message(const LocalMapEstimate& map, const std::string& vehicle_id);
  void report_fusion();
  // The ODOM_FAULT_* bits of one frame's estimate (IMU gap, too few features), counted on the heartbeat.
  std::uint32_t frame_faults(const FrameEstimate& e);
  void log_camera_calibration(std::int64_t stamp_ns);
  // Before the first frame IMU covers: start from the checkpoint read at construction if it is fresh enough.
  void resume_if_possible(std::int64_t frame_ns);
  // After a frame: the checkpoint, once per checkpoint_every_s while the alignment is declared.
  void write_checkpoint_if_due(const FrameEstimate& e);

  dds::Counters& counters_;
  SlidingWindowEstimator estimator_;
  GlobalFusion fusion_;
  std::unique_ptr<twin::EnuFrame> enu_;  // lat/lon/alt -> W (null without an origin)
  std::map<std::string, unsigned long long> reported_;  // fusion counts already in the heartbeat
  // ODOM_FAULT_* bits met since the last Odometry: set from DDS callbacks and the worker, taken by the next Odometry.
  std::atomic<std::uint32_t> faults_{0};
  FrameGapDetector frame_gaps_;
  unsigned long long odom_seq_ = 0, map_seq_ = 0;
  std::int64_t calibration_logged_ns_ = 0;  // stamp of the last log line of the camera rotation calibration
  EstimatorNodeOptions options_;
  std::optional<EstimatorCheckpoint> checkpoint_;  // read at start, used (or not) at the first frame
  std::int64_t first_imu_ns_ = -1;  // stamp of the first IMU sample this process got
  std::int64_t checkpoint_written_ns_ = -1;
};

}  // namespace twinslam::estimator
