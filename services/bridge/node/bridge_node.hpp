#pragma once
// The bridge's DDS side: every topic of the table is subscribed and each message goes to the WebSocket server as the
// CDR bytes DDS sent (channel = topic, schema = the project's IDL, as in MCAP recordings), so Foxglove decodes every
// field live; and the messages Foxglove's panels draw are also sent in its well-known schemas (JSON; per-vehicle
// channels advertised as their vehicle appears, twin tiles latched for late viewers: common/foxglove). Readers: the
// table's own profiles for results, tiles and control (a late bridge still gets the latched tiles), best effort for
// the high-rate sensor streams (a viewer must not hold back a lockstep replay). Counters: messages_in,
// tiles_undecodable, and the server's clients_accepted, frames_sent, frames_dropped.
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "twinslam/bridge/bridge_config.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/node.hpp"
#include "twinslam/foxglove/derived_channels.hpp"
#include "ws_server.hpp"

namespace twinslam::bridge {

// One channel per topic of dds::topics::kAll, ids from 1 in the table's order.
std::vector<Channel> dds_channels();

// A vehicle's ground truth for the view (`twinslam-bridge --truth VEHICLE=FILE`).
struct VehicleTruth {
  std::string vehicle_id;
  std::vector<foxglove::StampedPoseW> T_WB;
};
// "VEHICLE=FILE" (TUM T_WB, the dataset's groundtruth.tum) read; InputError / UsageError naming the file or the text.
VehicleTruth load_vehicle_truth(const std::string& spec);

class BridgeNode {
 public:
  // config.origin (if set) and `truth` are in place before the first message is read.
  BridgeNode(dds::Node& node, dds::Counters& counters, const BridgeConfig& config, std::vector<VehicleTruth> truth = {});
  ~BridgeNode();  // closes the node's readers first
  BridgeNode(const BridgeNode&) = delete;
  BridgeNode& operator=(const BridgeNode&) = delete;
  unsigned short port() const { return server_.port(); }

 private:
  // Sends the well-known forms of one message, advertising channels the first time their topic appears.
  void publish_derived(std::vector<foxglove::DerivedMessage> derived, std::uint64_t time_ns);

  dds::Node& node_;
  dds::Counters& counters_;
  WsServer server_;
  foxglove::DerivedChannels derived_;
  std::mutex channels_mutex_;
  std::map<std::string, std::uint32_t> derived_ids_;  // Foxglove topic -> channel id
  std::uint32_t next_id_ = 0;
};

}  // namespace twinslam::bridge
