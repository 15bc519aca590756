#include "records.hpp"

namespace twinslam::mcap::detail {
namespace {

std::size_t begin(Bytes& out, Op op) { return out.begin_record(static_cast<std::uint8_t>(op)); }

// Map<uint16, uint64> (https://mcap.dev/spec#mapkey_type-value_type): uint32 byte length, then key/value pairs.
void append_id_map(Bytes& out, const std::map<std::uint16_t, std::uint64_t>& map) {
  const std::size_t mark = out.begin_u32_length();
  for (const auto& [key, value] : map) {
    out.u16(key);
    out.u64(value);
  }
  out.end_u32_length(mark);
}

}  // namespace

void append_header(Bytes& out, const std::string& profile, const std::string& library) {
  const std::size_t mark = begin(out, Op::Header);
  out.string(profile);
  out.string(library);
  out.end_record(mark);
}

void append_schema(Bytes& out, const SchemaRecord& r) {
  const std::size_t mark = begin(out, Op::Schema);
  out.u16(r.id);
  out.string(r.name);
  out.string(r.encoding);
  out.string(r.data);  // uint32 length-prefixed Bytes: the same layout as a String
  out.end_record(mark);
}

void append_channel(Bytes& out, const ChannelRecord& r) {
  const std::size_t mark = begin(out, Op::Channel);
  out.u16(r.id);
  out.u16(r.schema_id);
  out.string(r.topic);
  out.string(r.message_encoding);
  const std::size_t map_mark = out.begin_u32_length();  // Map<string, string>
  for (const auto& [key, value] : r.metadata) {
    out.string(key);
    out.string(value);
  }
  out.end_u32_length(map_mark);
  out.end_record(mark);
}

void append_message(Bytes& out, const MessageRecord& r) {
  const std::size_t mark = begin(out, Op::Message);
  out.u16(r.channel_id);
  out.u32(r.sequence);
  out.u64(r.log_time);
  out.u64(r.publish_time);
  out.raw(r.data, r.size);  // no length prefix: the data runs to the end of the record
  out.end_record(mark);
}

void append_chunk_prefix(Bytes& out, const ChunkHeader& h) {
  static const std::string kNoCompression;
  // Content: 8 + 8 + 8 + 4 + (4 + 0) compression + 8 records length + the records.
  out.u8(static_cast<std::uint8_t>(Op::Chunk));
  out.u64(8 + 8 + 8 + 4 + 4 + kNoCompression.size() + 8 + h.uncompressed_size);
  out.u64(h.message_start_time);
  out.u64(h.message_end_time);
  out.u64(h.uncompressed_size);
  out.u32(h.uncompressed_crc);
  out.string(kNoCompression);
  out.u64(h.uncompressed_size);  // records length: compressed == uncompressed
}

void append_message_index(Bytes& out, std::uint16_t channel_id, const IndexEntries& entries) {
  const std::size_t mark = begin(out, Op::MessageIndex);
  out.u16(channel_id);
  const std::size_t array_mark = out.begin_u32_length();  // Array<Tuple<Timestamp, uint64>>
  for (const auto& [log_time, offset] : entries) {
    out.u64(log_time);
    out.u64(offset);
  }
  out.end_u32_length(array_mark);
  out.end_record(mark);
}

void append_chunk_index(Bytes& out, const ChunkIndexRecord& r) {
  const std::size_t mark = begin(out, Op::ChunkIndex);
  out.u64(r.message_start_time);
  out.u64(r.message_end_time);
  out.u64(r.chunk_start_offset);
  out.u64(r.chunk_length);
  append_id_map(out, r.message_index_offsets);
  out.u64(r.message_index_length);
  out.string("");  // compression
  out.u64(r.records_size);  // compressed_size
  out.u64(r.records_size);  // uncompressed_size
  out.end_record(mark);
}

void append_statistics(Bytes& out, const StatisticsRecord& r) {
  const std::size_t mark = begin(out, Op::Statistics);
  out.u64(r.message_count);
  out.u16(r.schema_count);
  out.u32(r.channel_count);
  out.u32(0);  // attachment_count: this writer writes no Attachment records
  out.u32(0);  // metadata_count: nor Metadata records
  out.u32(r.chunk_count);
  out.u64(r.message_start_time);
  out.u64(r.message_end_time);
  append_id_map(out, r.channel_message_counts);
  out.end_record(mark);
}

void append_summary_offset(Bytes& out, Op group, std::uint64_t group_start, std::uint64_t group_length) {
  const std::size_t mark = begin(out, Op::SummaryOffset);
  out.u8(static_cast<std::uint8_t>(group));
  out.u64(group_start);
  out.u64(group_length);
  out.end_record(mark);
}

void append_data_end(Bytes& out, std::uint32_t data_section_crc) {
  const std::size_t mark = begin(out, Op::DataEnd);
  out.u32(data_section_crc);
  out.end_record(mark);
}

void append_footer_prefix(Bytes& out, std::uint64_t summary_start, std::uint64_t summary_offset_start) {
  out.u8(static_cast<std::uint8_t>(Op::Footer));
  out.u64(8 + 8 + 4);  // the Footer is never extended (spec, "Records"): its length is fixed
  out.u64(summary_start);
  out.u64(summary_offset_start);
}

}  // namespace twinslam::mcap::detail
