#pragma once
// Sensor faults injected into a replay (issue 15 item 3): what a failing driver, cable or receiver does to a stream,
// applied to the samples ingest publishes, never to the dataset on disk. The consumers must meet each with defined
// behaviour (counted, reported on the Odometry and the heartbeat, never a crash, never a silent wrong output).
// Config (ingest.yaml, section `faults`; every window off unless its at_s is given):
//   faults:
//     imu_nan:          {at_s: 10, duration_s: 0.05}  # IMU samples published with NaN readings
//     imu_inf:          {at_s: 10, duration_s: 0.05}  # ... with infinite readings
//     imu_gap:          {at_s: 12, duration_s: 1.0}   # IMU samples not published
//     imu_duplicate:    {at_s: 14, duration_s: 0.5}   # every IMU sample published twice
//     imu_out_of_order: {at_s: 16, duration_s: 0.5}   # consecutive IMU samples published in swapped pairs
//     frame_drop:       {at_s: 18, duration_s: 1.0}   # camera frames not published
//     frame_black:      {at_s: 20, duration_s: 0.5}   # images all 0 (feature frames: no features)
//     frame_saturated:  {at_s: 22, duration_s: 0.5}   # images all 255 (feature frames: no features)
//     gnss_jump:        {at_s: 24, duration_s: 5, east_m: 50}  # GNSS fixes moved east_m metres east
#include <cstdint>
#include <string>
#include <vector>

#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/ingest/replay.hpp"

namespace twinslam::ingest {

struct FaultWindow {
  double at_s = -1.0;       // start, seconds after the dataset's first sample; < 0: off
  double duration_s = 0.0;  // [s]
  double east_m = 50.0;     // gnss_jump only: the offset [m, east]
  bool enabled() const { return at_s >= 0.0; }
  bool contains(std::int64_t stamp_ns, std::int64_t t0_ns) const;
};

struct FaultConfig {
  FaultWindow imu_nan, imu_inf, imu_gap, imu_duplicate, imu_out_of_order;
  FaultWindow frame_drop, frame_black, frame_saturated;
  FaultWindow gnss_jump;
  bool any() const;
  // Throws InputError "SOURCE: ingest key 'faults.K.duration_s': ..." for a negative or non-finite value.
  void validate(const std::string& source) const;
};

void bind_fault_config(yaml::Fields& faults_section, FaultConfig& config);

// What ingest does with one replay event.
enum class FaultAction {
  kPublish,    // as recorded
  kDrop,       // not published (imu_gap, frame_drop)
  kNan,        // IMU readings NaN
  kInf,        // IMU readings +inf
  kTwice,      // IMU sample published twice in a row
  kBlack,      // image all 0 / feature frame empty
  kSaturated,  // image all 255 / feature frame empty
  kGnssShift,  // GNSS fix moved by gnss_jump.east_m
};

struct PlannedEvent {
  ReplayEvent event;
  FaultAction action = FaultAction::kPublish;
  const char* fault = nullptr;  // the config key of the fault that touched it (out-of-order: both samples of a pair)
};

// The replay with the faults applied, in publication order: out-of-order windows swap consecutive IMU samples
// pairwise (so each second sample goes out with an earlier stamp than the one before it).
std::vector<PlannedEvent> plan_faults(const std::vector<ReplayEvent>& events, const FaultConfig& config);

// "imu_nan 12 samples, frame_drop 20 frames, ...": one line for the log, of the faults that touched something.
std::string describe_plan(const std::vector<PlannedEvent>& plan);

}  // namespace twinslam::ingest
