#pragma once
// Records DDS messages into an MCAP file (issue 16 item 3): one channel per topic of dds::topics::kAll (topic name,
// message encoding "cdr": the bytes DDS puts on the wire, encapsulation header included) and one schema per message
// type ("omgidl": the project's IDL as one text, schema name twinslam::msg::<Type>), so Foxglove and the official
// MCAP readers decode every message without this project's code. Log time = when this process received the message
// (wall clock, ns since the Unix epoch), publish time = the same: DDS does not carry the writer's send time to us.
// The same messages in Foxglove's well-known schemas (common/foxglove: poses, path, GNSS, landmark clouds, twin tiles,
// registration health) go to JSON channels (message encoding "json", schema encoding "jsonschema") created as their
// topic first appears, the channels the bridge serves live. Thread-safe: the monitor's readers call record() from
// Fast DDS threads.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "twinslam/dds/topics.hpp"
#include "twinslam/foxglove/derived_channels.hpp"

namespace twinslam::mcap {
class Writer;
}

namespace twinslam::cli {

class McapRecorder {
 public:
  // Creates (truncates) `path`; throws InputError naming it if it cannot be written.
  explicit McapRecorder(const std::string& path);
  ~McapRecorder();
  McapRecorder(const McapRecorder&) = delete;
  McapRecorder& operator=(const McapRecorder&) = delete;

  void record(const dds::TopicSpec& topic, const std::vector<std::uint8_t>& cdr);
  void record(const std::vector<foxglove::DerivedMessage>& well_known);
  // Writes the summary and index; later record() calls are ignored. Throws InputError if the disk write fails.
  void close();
  // Messages recorded per topic name (DDS topics and well-known channels).
  std::map<std::string, std::uint64_t> counts() const;
  const std::string& path() const { return path_; }

 private:
  struct Channel {
    std::uint16_t id = 0;
    std::uint32_t sequence = 0;
    std::uint64_t count = 0;
  };
  std::string path_;
  std::unique_ptr<mcap::Writer> writer_;
  mutable std::mutex mutex_;
  std::map<std::string_view, Channel> channels_;  // by topic name (the names are the table's string literals)
  std::map<std::string, Channel> json_channels_;  // well-known channels by Foxglove topic
  std::map<std::string_view, std::uint16_t> json_schemas_;  // by schema name (static strings of common/foxglove)
  void write(Channel& c, const std::uint8_t* data, std::size_t size);
  bool closed_ = false;
};

}  // namespace twinslam::cli
