#pragma once
// The MCAP records this writer emits, each appended to a Bytes as `<opcode><uint64 length><content>` with the
// fields in the order of https://mcap.dev/spec#records. Only what a chunked, indexed, uncompressed file needs:
// no Attachment or Metadata records.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bytes.hpp"

namespace twinslam::mcap::detail {

// https://mcap.dev/spec#magic: 0x89 "MCAP" major version '0' "\r\n", at both ends of the file.
inline constexpr std::array<std::uint8_t, 8> kMagic{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum class Op : std::uint8_t {
  Header = 0x01,
  Footer = 0x02,
  Schema = 0x03,
  Channel = 0x04,
  Message = 0x05,
  Chunk = 0x06,
  MessageIndex = 0x07,
  ChunkIndex = 0x08,
  Statistics = 0x0B,
  SummaryOffset = 0x0E,
  DataEnd = 0x0F,
};

struct SchemaRecord {
  std::uint16_t id = 0;
  std::string name, encoding, data;
};

struct ChannelRecord {
  std::uint16_t id = 0, schema_id = 0;
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};

struct MessageRecord {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0, publish_time = 0;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// The Chunk record's fields before `records` (https://mcap.dev/spec#chunk-op0x06).
struct ChunkHeader {
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
};

// (log_time, offset of the Message record in the uncompressed chunk records) per message of one channel.
using IndexEntries = std::vector<std::pair<std::uint64_t, std::uint64_t>>;

struct ChunkIndexRecord {
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::uint64_t chunk_start_offset = 0, chunk_length = 0;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::uint64_t records_size = 0;  // compressed_size == uncompressed_size: no compression
};

struct StatisticsRecord {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0, chunk_count = 0;
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

void append_header(Bytes& out, const std::string& profile, const std::string& library);
void append_schema(Bytes& out, const SchemaRecord& r);
void append_channel(Bytes& out, const ChannelRecord& r);
void append_message(Bytes& out, const MessageRecord& r);
// Everything of the Chunk record up to and including the `records` length: the records bytes follow it.
void append_chunk_prefix(Bytes& out, const ChunkHeader& h);
void append_message_index(Bytes& out, std::uint16_t channel_id, const IndexEntries& entries);
void append_chunk_index(Bytes& out, const ChunkIndexRecord& r);
void append_statistics(Bytes& out, const StatisticsRecord& r);
void append_summary_offset(Bytes& out, Op group, std::uint64_t group_start, std::uint64_t group_length);
void append_data_end(Bytes& out, std::uint32_t data_section_crc);
// The Footer up to and including summary_offset_start: summary_crc covers these bytes, so it is appended after.
void append_footer_prefix(Bytes& out, std::uint64_t summary_start, std::uint64_t summary_offset_start);

}  // namespace twinslam::mcap::detail
