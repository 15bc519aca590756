#pragma once
// The bridge's WebSocket server (Boost.Beast, one I/O thread): accepts clients that ask for the Foxglove subprotocol,
// sends each serverInfo and the channel list, applies their Subscribe / Unsubscribe, and fans published messages out
// as Message Data frames to the subscribed ones. Channels can be added while clients are connected (advertised to
// them at once): the bridge's per-vehicle channels appear with their vehicle. publish() never blocks the caller (a
// DDS listener thread): frames are queued per client and, past `max_queued` frames, the oldest are dropped and
// counted — a slow viewer must never slow the pipeline. A plain HTTP GET on the same port gets the web view's files
// from `web_root` (static_files.hpp): http://HOST:PORT/ opens the view, which connects back to ws://HOST:PORT/.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "twinslam/bridge/foxglove_protocol.hpp"
#include "twinslam/dds/heartbeat.hpp"

namespace twinslam::bridge {

class WsServer {
 public:
  // Listens on `address`:`port` (0: any free port, see port()). Throws std::runtime_error naming the address when it
  // cannot listen. Counts clients_accepted, frames_sent (Message Data written) and frames_dropped (from a full
  // client queue) in `counters`, which must outlive the server.
  WsServer(const std::string& address, unsigned short port, std::vector<Channel> channels, std::string name,
           std::size_t max_queued, dds::Counters& counters, std::filesystem::path web_root = {});
  ~WsServer();  // closes every client and joins the I/O thread
  WsServer(const WsServer&) = delete;
  WsServer& operator=(const WsServer&) = delete;

  unsigned short port() const;
  // Sends `payload` on `channel_id` to every client subscribed to it. Thread-safe, non-blocking. A `latch_key`
  // (any string) also keeps the payload as the last of that key on the channel: a later subscriber gets every kept
  // one first (the twin's tiles, which arrive once).
  void publish(std::uint32_t channel_id, std::uint64_t receive_time_ns,
               std::shared_ptr<const std::vector<std::uint8_t>> payload,
               const std::optional<std::string>& latch_key = std::nullopt);
  // Adds channels (ids not used yet) and advertises them to every connected client. Thread-safe, non-blocking.
  void advertise(std::vector<Channel> channels);
  std::uint64_t clients() const;  // connected now

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace twinslam::bridge
