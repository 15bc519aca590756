#pragma once
// MCAP writer (https://mcap.dev/spec, major version 0): messages go into uncompressed Chunks followed by their
// Message Index records; close() writes Data End, the summary (Schema, Channel, Statistics, Chunk Index groups),
// the Summary Offset records and the Footer, so indexed readers (Foxglove, @mcap/core) seek without scanning.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace twinslam::mcap {

struct WriterOptions {
  std::string profile;                  // Header.profile ("" or e.g. "ros2"); we write ""
  std::string library = "twinslam";     // Header.library
  std::size_t chunk_size = 1u << 20;    // uncompressed bytes per chunk before it is closed [bytes]
};

class Writer {
 public:
  // Opens (truncates) `path`, writes the magic and the Header. Throws twinslam::InputError("PATH: cannot write: ...").
  explicit Writer(const std::string& path, WriterOptions options = {});
  ~Writer();  // close() if still open; never throws (logs nothing, swallows)
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Returns ids from 1 (0 is "no schema" in the spec). Schemas/channels are written before their first message
  // in the data section and again in the summary. Both take the writer's mutex (topics appear on DDS threads).
  // Throws std::logic_error for an unknown schema id (other than 0), after close(), or past 65535 ids.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});

  // Thread-safe (a mutex): called from several DDS reader threads. Throws std::logic_error for an unknown channel
  // or after close(); InputError naming the path if the disk write of a full chunk fails.
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
             std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size);

  // Flushes the open chunk, writes Data End, the summary, the Summary Offset records, the Footer and the closing
  // magic. Idempotent. Throws InputError naming the path if the disk write fails.
  void close();

  std::uint64_t message_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace twinslam::mcap
