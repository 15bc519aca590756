#pragma once
// Watches every topic of the table: message counts, matched writers, and the latest heartbeat of each service.
// Used by `twinslam topics` (best effort, never slows the pipeline) and by `twinslam run` (reliable, exact counts).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "twinslam/dds/node.hpp"
#include "twinslam/foxglove/derived_channels.hpp"

namespace twinslam::cli {

struct TopicStats {
  std::string name, type;
  unsigned long long messages = 0;
  int writers = 0;  // matched writers now
};

struct ServiceInfo {
  std::string service, instance, vehicle_id, state;
  unsigned long long uptime_ms = 0;
  std::map<std::string, unsigned long long> counters;
};

// Optional callbacks for topics whose content (not just count) a tool records.
struct MonitorHooks {
  std::function<void(const msg::Image&)> image;
  std::function<void(const msg::FeatureFrame&)> features;
  std::function<void(const msg::Odometry&)> odometry;
  std::function<void(const msg::Registration&)> registration;
  std::function<void(const msg::LocalMap&)> local_map;
  // When set, the five hooks above see only this vehicle's messages (a shared edge answers every vehicle in
  // partitions a run also reads); the cdr and well_known hooks and the counts see every message.
  std::optional<std::string> vehicle;
  // Every message of every topic as its CDR bytes (dds/cdr.hpp), e.g. for an MCAP recording; serialized only when set.
  std::function<void(const dds::TopicSpec&, const std::vector<std::uint8_t>&)> cdr;
  // Every message's forms in Foxglove's well-known schemas (common/foxglove, as the bridge sends them); converted
  // only when set.
  std::function<void(const std::vector<foxglove::DerivedMessage>&)> well_known;
};

class TopicMonitor {
 public:
  TopicMonitor(dds::Node& node, bool reliable, MonitorHooks hooks = {});
  // Closes the node's readers first: their callbacks use this monitor (and the hooks' captures), and a message
  // arriving while it is destroyed crashed `twinslam topics` (exit 139) about one run in five with a pipeline up.
  ~TopicMonitor();
  TopicMonitor(const TopicMonitor&) = delete;
  TopicMonitor& operator=(const TopicMonitor&) = delete;
  std::vector<TopicStats> stats() const;
  std::vector<ServiceInfo> services() const;  // latest heartbeat per instance, sorted by service
  // True once every named service has announced ready/running/done.
  bool all_ready(const std::vector<std::string>& services) const;
  // The well-known channels' state: a run gives it the dataset's truth and origin for its MCAP recording.
  foxglove::DerivedChannels& well_known() { return well_known_; }

 private:
  struct Entry {
    const dds::TopicSpec* spec;
    const dds::ReaderStatus* status;
  };
  dds::Node& node_;
  std::vector<Entry> entries_;
  MonitorHooks hooks_;
  foxglove::DerivedChannels well_known_;  // for hooks_.well_known
  mutable std::mutex mutex_;
  std::map<std::string, ServiceInfo> services_;
};

}  // namespace twinslam::cli
