#include "bridge_node.hpp"

#include <twinslam/IdlText.h>

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

BridgeNode::BridgeNode(dds::Node& node, dds::Counters& counters, const BridgeConfig& config)
    : node_(node),
      server_(config.address, static_cast<unsigned short>(config.port), dds_channels(), "twinslam-bridge",
              static_cast<std::size_t>(config.max_queued), counters) {
  std::uint32_t id = 0;
  for (const dds::TopicSpec& spec : dds::topics::kAll) {
    const std::uint32_t channel = ++id;
    const bool sensor = spec.family == dds::QosFamily::Sensor;
    const std::string_view profile = sensor ? dds::kMonitorReaderProfile : dds::reader_profile(spec.family);
    dds::with_message_type(spec, [&]<class T>() {
      node.subscribe<T>(spec, [this, channel, &counters](const T& m) {
        counters.add("messages_in");
        if (server_.clients() == 0) return;  // nobody watches: no serialization
        server_.publish(channel, unix_time_ns(), std::make_shared<const std::vector<std::uint8_t>>(dds::to_cdr(m)));
      }, profile);
    });
  }
}

BridgeNode::~BridgeNode() { node_.close_readers(); }

}  // namespace twinslam::bridge
