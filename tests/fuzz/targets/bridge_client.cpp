// What a Foxglove client may send the bridge (services/bridge/lib foxglove_protocol.hpp): any text messages, split
// at kPartSeparator, applied in order to one client's subscriptions. Nothing may throw (the bridge's I/O thread serves
// every client), every answer is a status message, and no subscription may point at a channel that does not exist.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "harness.hpp"
#include "twinslam/bridge/foxglove_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  twinslam::bridge::ClientSubscriptions subs({1, 2, 3, 11});
  for (const std::string_view part : twinslam::fuzz::split_parts(data, size, 16)) {
    for (const std::string& status : subs.apply(std::string(part))) {
      const auto j = nlohmann::json::parse(status, nullptr, false);
      if (!j.is_object() || j.value("op", "") != "status") __builtin_trap();
    }
  }
  std::size_t routed = 0;
  for (const std::uint32_t channel : {0u, 1u, 2u, 3u, 4u, 11u, 12u}) routed += subs.subscriptions_of(channel).size();
  if (routed != subs.size() || !subs.subscriptions_of(0).empty() || !subs.subscriptions_of(12).empty()) {
    __builtin_trap();  // a subscription on a channel the bridge never advertised
  }
  return 0;
}
