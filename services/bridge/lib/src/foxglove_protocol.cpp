#include "twinslam/bridge/foxglove_protocol.hpp"

#include <nlohmann/json.hpp>

namespace twinslam::bridge {

using nlohmann::json;

std::string server_info_json(const std::string& name, const std::string& session_id) {
  // No optional capability: the bridge only streams (no client publishing, parameters, services or time).
  return json{{"op", "serverInfo"}, {"name", name}, {"capabilities", json::array()}, {"sessionId", session_id}}.dump();
}

std::string advertise_json(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id}, {"topic", c.topic}, {"encoding", c.encoding}, {"schemaName", c.schema_name},
                    {"schema", c.schema}, {"schemaEncoding", c.schema_encoding}});
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string status_json(int level, const std::string& message) {
  return json{{"op", "status"}, {"level", level}, {"message", message}}.dump();
}

std::vector<std::uint8_t> message_data(std::uint32_t subscription_id, std::uint64_t receive_time_ns,
                                       const std::uint8_t* payload, std::size_t size) {
  std::vector<std::uint8_t> out;
  out.reserve(1 + 4 + 8 + size);
  out.push_back(0x01);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(subscription_id >> (8 * i)));
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(receive_time_ns >> (8 * i)));
  out.insert(out.end(), payload, payload + size);
  return out;
}

namespace {

using Subscriptions = std::map<std::uint32_t, std::uint32_t>;  // subscription id -> channel id

// A JSON number that is an unsigned 32-bit integer, as ids are.
bool as_u32(const json& v, std::uint32_t* out) {
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0xffffffffULL) return false;
  *out = static_cast<std::uint32_t>(v.get<std::uint64_t>());
  return true;
}

void subscribe(const json& j, const std::set<std::uint32_t>& channels, Subscriptions& by_id,
               std::vector<std::string>* status) {
  if (!j.contains("subscriptions") || !j["subscriptions"].is_array()) {
    status->push_back(status_json(2, "subscribe without a 'subscriptions' array"));
    return;
  }
  for (const json& s : j["subscriptions"]) {
    std::uint32_t id = 0, channel = 0;
    if (!s.is_object() || !s.contains("id") || !s.contains("channelId") || !as_u32(s["id"], &id) ||
        !as_u32(s["channelId"], &channel)) {
      status->push_back(status_json(2, "subscription needs unsigned 32-bit 'id' and 'channelId'"));
    } else if (channels.count(channel) == 0) {
      status->push_back(status_json(2, "subscription " + std::to_string(id) + ": no channel " +
                                           std::to_string(channel)));
    } else if (!by_id.emplace(id, channel).second) {
      status->push_back(status_json(2, "subscription id " + std::to_string(id) + " is already in use"));
    }
  }
}

void unsubscribe(const json& j, Subscriptions& by_id, std::vector<std::string>* status) {
  if (!j.contains("subscriptionIds") || !j["subscriptionIds"].is_array()) {
    status->push_back(status_json(2, "unsubscribe without a 'subscriptionIds' array"));
    return;
  }
  for (const json& v : j["subscriptionIds"]) {
    std::uint32_t id = 0;
    if (!as_u32(v, &id) || by_id.erase(id) == 0) {
      status->push_back(status_json(1, "unsubscribe: no subscription " + v.dump()));
    }
  }
}

}  // namespace

std::vector<std::string> ClientSubscriptions::apply(const std::string& text) {
  std::vector<std::string> status;
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) {
    status.push_back(status_json(2, "not a JSON object with a string 'op'"));
    return status;
  }
  const std::string op = j["op"];
  if (op == "subscribe") {
    subscribe(j, channels_, by_id_, &status);
  } else if (op == "unsubscribe") {
    unsubscribe(j, by_id_, &status);
  } else {
    status.push_back(status_json(1, "unsupported op '" + op + "' (this server only streams)"));
  }
  return status;
}

std::vector<std::uint32_t> ClientSubscriptions::subscriptions_of(std::uint32_t channel_id) const {
  std::vector<std::uint32_t> out;
  for (const auto& [id, channel] : by_id_) {
    if (channel == channel_id) out.push_back(id);
  }
  return out;
}

}  // namespace twinslam::bridge
