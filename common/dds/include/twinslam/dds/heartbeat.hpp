#pragma once
// Liveness of a service: its state and counters, published every `period` on the heartbeat topic.
// `twinslam topics`, `twinslam launch` and `twinslam run` read these to show and supervise the pipeline.
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "twinslam/dds/node.hpp"

namespace twinslam::dds {

// Named monotonically increasing counters ("imu_in", "frames_out", ...), safe to bump from any thread.
class Counters {
 public:
  void add(const std::string& name, unsigned long long n = 1);
  unsigned long long get(const std::string& name) const;
  std::map<std::string, unsigned long long> snapshot() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, unsigned long long> values_;
};

class HeartbeatPublisher {
 public:
  HeartbeatPublisher(Node& node, const Counters& counters,
                     std::chrono::milliseconds period = std::chrono::milliseconds(500));
  ~HeartbeatPublisher();  // publishes a final SVC_STOPPING beat
  void set_state(msg::ServiceState state);
  void beat();  // publish now (state changes are sent at once)

 private:
  Node& node_;
  const Counters& counters_;
  Writer<msg::Heartbeat> writer_;
  std::string instance_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<msg::ServiceState> state_{msg::SVC_STARTING};
  std::mutex beat_mutex_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace twinslam::dds
