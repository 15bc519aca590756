#include "bridge_node.hpp"

#include <type_traits>

#include <twinslam/IdlText.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/wall_clock.hpp"
#include "twinslam/dds/cdr.hpp"
#include "twinslam/dds/dispatch.hpp"

namespace twinslam::bridge {

std::vector<Channel> dds_channels() {
  std::vector<Channel> out;
  for (const dds::TopicSpec& t : dds::topics::kAll) {
    out.push_back({static_cast<std::uint32_t>(out.size() + 1), std::string(t.name), "cdr", std::string(t.type_name),
                   "omgidl", std::string(msg::kIdlText)});
  }
  return out;
}

VehicleTruth load_vehicle_truth(const std::string& spec) {
  const std::size_t eq = spec.find('=');
  if (eq == std::string::npos || eq + 1 == spec.size()) {
    throw UsageError("--truth '" + spec + "': expected VEHICLE=FILE (a TUM file of T_WB)");
  }
  return {spec.substr(0, eq), foxglove::read_truth_tum(spec.substr(eq + 1))};
}

BridgeNode::BridgeNode(dds::Node& node, dds::Counters& counters, const BridgeConfig& config,
                       std::vector<VehicleTruth> truth)
    : node_(node),
      counters_(counters),
      server_(config.address, static_cast<unsigned short>(config.port), dds_channels(), "twinslam-bridge",
              static_cast<std::size_t>(config.max_queued), counters,
              config.web_root.empty() ? std::string(TWINSLAM_WEB_DIR) : config.web_root),
      next_id_(static_cast<std::uint32_t>(dds::topics::kAll.size())) {
  if (!config.origin.empty()) derived_.set_origin(config.origin);
  for (VehicleTruth& t : truth) derived_.set_truth(t.vehicle_id, std::move(t.T_WB));
  std::uint32_t id = 0;
  for (const dds::TopicSpec& spec : dds::topics::kAll) {
    const std::uint32_t channel = ++id;
    const bool sensor = spec.family == dds::QosFamily::Sensor;
    const std::string_view profile = sensor ? dds::kMonitorReaderProfile : dds::reader_profile(spec.family);
    dds::with_message_type(spec, [&]<class T>() {
      node.subscribe<T>(spec, [this, channel](const T& m) {
        counters_.add("messages_in");
        const std::uint64_t now = unix_time_ns();
        // Derived forms first: tiles are kept for late viewers, the path and LocalMaps (for the registered cloud)
        // even when nobody watches yet; other JSON only for a watcher.
        auto derived = derived_.on(m, server_.clients() > 0);
        if constexpr (std::is_same_v<T, msg::MapTile>) {
          if (derived.empty()) counters_.add("tiles_undecodable");  // its mesh does not decode
        }
        publish_derived(std::move(derived), now);
        if (server_.clients() == 0) return;  // nobody watches: no serialization
        server_.publish(channel, now, std::make_shared<const std::vector<std::uint8_t>>(dds::to_cdr(m)));
      }, profile);
    });
  }
}

BridgeNode::~BridgeNode() { node_.close_readers(); }

void BridgeNode::publish_derived(std::vector<foxglove::DerivedMessage> derived, std::uint64_t time_ns) {
  for (foxglove::DerivedMessage& d : derived) {
    std::uint32_t channel = 0;
    {
      std::lock_guard lock(channels_mutex_);
      auto [it, added] = derived_ids_.try_emplace(d.topic, next_id_ + 1);
      if (added) {
        ++next_id_;
        server_.advertise({{it->second, d.topic, "json", std::string(d.schema->name), "jsonschema",
                            std::string(d.schema->jsonschema)}});
      }
      channel = it->second;
    }
    server_.publish(channel, time_ns, std::make_shared<const std::vector<std::uint8_t>>(d.json.begin(), d.json.end()),
                    d.latch_key);
  }
}

}  // namespace twinslam::bridge
