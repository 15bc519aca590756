#pragma once
// Foxglove WebSocket protocol v1 (github.com/foxglove/ws-protocol docs/spec.md), the part a live viewer needs: the
// server announces itself (serverInfo) and its channels (advertise); a client subscribes to channels under ids of its
// choosing and receives Message Data frames (opcode 0x01, subscription id, receive time, payload). No sockets here:
// the bridge's node moves these bytes (services/bridge/node/ws_server.hpp).
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace twinslam::bridge {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

struct Channel {
  std::uint32_t id = 0;
  std::string topic;           // the DDS topic name
  std::string encoding;        // message encoding, e.g. "cdr"
  std::string schema_name;     // e.g. "twinslam::msg::Odometry"
  std::string schema_encoding; // e.g. "omgidl"
  std::string schema;          // the schema text
};

std::string server_info_json(const std::string& name, const std::string& session_id);
std::string advertise_json(const std::vector<Channel>& channels);
// level: 0 info, 1 warning, 2 error.
std::string status_json(int level, const std::string& message);
// Message Data: 0x01, uint32 subscription id, uint64 receive time [ns], payload (little endian).
std::vector<std::uint8_t> message_data(std::uint32_t subscription_id, std::uint64_t receive_time_ns,
                                       const std::uint8_t* payload, std::size_t size);

// One client's subscriptions. Never throws on what a client sends: a malformed or unsupported message, an unknown
// channel or a reused subscription id is answered with a status message and changes nothing else.
class ClientSubscriptions {
 public:
  explicit ClientSubscriptions(std::set<std::uint32_t> channel_ids) : channels_(std::move(channel_ids)) {}

  // Applies a text message from the client; returns the status messages to send back (none when all went well).
  std::vector<std::string> apply(const std::string& text);
  // Channels advertised after this client connected become subscribable.
  void add_channels(const std::vector<std::uint32_t>& channel_ids) {
    channels_.insert(channel_ids.begin(), channel_ids.end());
  }
  // Subscription id -> channel id.
  const std::map<std::uint32_t, std::uint32_t>& subscriptions() const { return by_id_; }
  // The client's subscription ids on `channel_id` (at most one per the spec, but a list costs nothing).
  std::vector<std::uint32_t> subscriptions_of(std::uint32_t channel_id) const;
  std::size_t size() const { return by_id_.size(); }

 private:
  std::set<std::uint32_t> channels_;
  std::map<std::uint32_t, std::uint32_t> by_id_;  // subscription id -> channel id
};

}  // namespace twinslam::bridge
