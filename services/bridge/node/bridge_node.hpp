#pragma once
// The bridge's DDS side: every topic of the table is subscribed and each message goes to the WebSocket server as the
// CDR bytes DDS sent (channel = topic, schema = the project's IDL, as in MCAP recordings), so Foxglove decodes every
// field live. Readers: the table's own profiles for results, tiles and control (a late bridge still gets the latched
// tiles), best effort for the high-rate sensor streams (a viewer must not hold back a lockstep replay). Counters:
// messages_in, and the server's clients_accepted, frames_sent, frames_dropped.
#include <memory>
#include <vector>

#include "twinslam/bridge/bridge_config.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "ws_server.hpp"

namespace twinslam::bridge {

// One channel per topic of dds::topics::kAll, ids from 1 in the table's order.
std::vector<Channel> dds_channels();

class BridgeNode {
 public:
  BridgeNode(dds::Node& node, dds::Counters& counters, const BridgeConfig& config);
  ~BridgeNode();  // closes the node's readers first
  BridgeNode(const BridgeNode&) = delete;
  BridgeNode& operator=(const BridgeNode&) = delete;
  unsigned short port() const { return server_.port(); }

 private:
  dds::Node& node_;
  WsServer server_;
};

}  // namespace twinslam::bridge
