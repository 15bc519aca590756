#pragma once
// What lockstep replay (--max) waits on, without the topics (ingest_node.cpp wires them): which consumer services
// announced they are ready (Heartbeat READY or RUNNING) and the newest camera frame each acknowledged (FrameAck).
// Only this vehicle's samples count — a fleet shares the topics, and uav2's estimator finishing a frame must not let
// uav1's ingest send its next one; heartbeats with an empty vehicle_id come from services that serve every vehicle.
// Fed arbitrary samples by tests/fuzz/targets/dds_ingest.cpp. Thread-safe: Fast DDS calls the readers from its
// threads while run() polls.
#include <cstdint>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "twinslam/dds/types.hpp"

namespace twinslam::ingest {

class AckBook {
 public:
  explicit AckBook(std::string vehicle_id) : vehicle_id_(std::move(vehicle_id)) {}

  void on_ack(const msg::FrameAck& ack);
  void on_heartbeat(const msg::Heartbeat& hb);

  // Every service in `services` has acknowledged a frame stamped `stamp_ns` or later (true for an empty list).
  bool all_acked(const std::vector<std::string>& services, std::int64_t stamp_ns) const;
  // Every service in `services` announced READY or RUNNING for this vehicle (or for every vehicle).
  bool all_ready(const std::vector<std::string>& services) const;
  // Those of `services` not yet heard announcing READY or RUNNING, in their order (the start-up timeout names them).
  std::vector<std::string> not_ready(const std::vector<std::string>& services) const;
  // The newest frame `service` acknowledged; INT64_MIN if none.
  std::int64_t last_acked(const std::string& service) const;

 private:
  const std::string vehicle_id_;
  mutable std::mutex mutex_;
  std::map<std::string, std::int64_t> acked_;  // service -> newest acknowledged frame stamp [ns]
  std::set<std::string> ready_;                // services that announced READY or RUNNING
};

}  // namespace twinslam::ingest
