#pragma once
// The open Chunk (https://mcap.dev/spec#chunk-op0x06): the uncompressed records (Schema, Channel, Message) and,
// per channel, the (log_time, offset) entries of its Message Index record (spec#message-index-op0x07).
#include <cstdint>
#include <map>

#include "records.hpp"

namespace twinslam::mcap::detail {

class ChunkBuilder {
 public:
  void add_schema(const SchemaRecord& r) { append_schema(records_, r); }
  void add_channel(const ChannelRecord& r) { append_channel(records_, r); }
  void add_message(const MessageRecord& r);

  bool empty() const { return records_.size() == 0; }
  std::size_t size() const { return records_.size(); }
  const Bytes& records() const { return records_; }
  // Times are those of the messages (0 and 0 when there are none, as the spec asks); the CRC is the records'.
  ChunkHeader header() const;
  // The chunk's Message Index records, one per channel with messages, for a file where they start at offset
  // `first`; fills the channel -> file offset map of the Chunk Index.
  void append_message_indexes(Bytes& out, std::uint64_t first, std::map<std::uint16_t, std::uint64_t>& offsets) const;
  void clear();

 private:
  Bytes records_;
  std::map<std::uint16_t, IndexEntries> index_;
  std::uint64_t start_time_ = 0, end_time_ = 0;
};

}  // namespace twinslam::mcap::detail
