#pragma once
// The ingest service's DDS shell: publishes a loaded dataset as Imu, Image and GnssFix in timestamp order.
//  --realtime: paced by sensor time (scaled by `speed`), nothing ever waits for consumers.
//  --max (lockstep): before camera frame k+1 is sent, every service named in `ack_from` has acknowledged frame k on
//  the frame_ack topic, and every reliable reader has acknowledged every sample; so nothing is lost and two runs see
//  the same data in the same order at every processing step.
#include <chrono>
#include <string>
#include <vector>

#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/camera/camera_config.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/faults.hpp"
#include "twinslam/ingest/features.hpp"

namespace twinslam::ingest {

struct WaitReaders {
  int imu = 0, image = 0, gnss = 0;
};
// "N" (imu and image), or "imu=N,image=N,gnss=N"; empty: `fallback` for imu and image. Throws UsageError.
WaitReaders parse_wait_readers(const std::string& text, int fallback);

struct IngestOptions {
  bool realtime = false;
  double speed = 1.0;                          // realtime pacing factor (2 = twice as fast)
  std::vector<std::string> ack_from;           // services that acknowledge each camera frame (lockstep)
  WaitReaders wait_readers;                    // matched readers per stream before the first sample
  std::chrono::milliseconds start_timeout{30000};
  std::chrono::milliseconds ack_timeout{30000};
  unsigned short camera_id = 0;
  FaultConfig faults;                          // sensor faults injected into the replay (none by default)
};

// Ideal feature tracks to publish as FeatureFrame instead of the images (sim --features), with the camera that
// turns their pixels into bearings.
struct FeatureReplay {
  std::vector<FeatureFrameRecord> frames;
  CameraConfig camera;
};

class IngestNode {
 public:
  // `features` may be null (images are published).
  IngestNode(dds::Node& node, const Dataset& dataset, IngestOptions options, const FeatureReplay* features = nullptr);
  ~IngestNode();  // closes the node's readers first: no callback may reach a destroyed member
  // Publishes the whole dataset (or until shutdown). Returns false if stopped early by a signal.
  // Throws std::runtime_error when a consumer does not acknowledge in time.
  bool run();

 private:
  class Impl;
  Impl* impl_;
};

}  // namespace twinslam::ingest
