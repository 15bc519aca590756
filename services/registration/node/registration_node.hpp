#pragma once
// The registration service's DDS shell (paper Sec. III-C on an edge server): LocalMap (every vehicle's landmark
// cloud per keyframe) and MapTile (the twin, latched) in; Registration out, keyed by vehicle. One worker thread
// serves the vehicles in turn; for each it keeps only the newest LocalMap not yet registered (a slower edge skips
// clouds instead of queueing them: `skipped` in the heartbeat), so the estimator is never held up by it. Tiles are
// decoded and indexed on the worker when they enter a vehicle's window. What a sample becomes is
// RegistrationHandler's (registration_handler.hpp, free of DDS).
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "registration_handler.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::registration {

class RegistrationNode {
 public:
  RegistrationNode(dds::Node& node, dds::Counters& counters, const RegistrationNodeOptions& options);
  ~RegistrationNode();
  RegistrationNode(const RegistrationNode&) = delete;
  RegistrationNode& operator=(const RegistrationNode&) = delete;

 private:
  struct Pending {
    std::shared_ptr<const msg::LocalMap> map;
    std::chrono::steady_clock::time_point arrived;
  };
  void run();
  void serve(const Pending& p);

  dds::Counters& counters_;
  dds::Writer<msg::Registration> writer_;
  RegistrationHandler handler_;  // worker only

  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, Pending> pending_;               // newest LocalMap per vehicle
  std::deque<std::shared_ptr<const msg::MapTile>> tiles_in_;
  std::string last_served_;                              // round robin over vehicles
  std::map<std::string, std::size_t> local_maps_of_;     // LocalMaps received per vehicle (logged at the end)
  bool stop_ = false;
  std::thread worker_;  // last
};

}  // namespace twinslam::registration
