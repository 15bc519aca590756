#include "twinslam/mcap/writer.hpp"

#include <algorithm>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "chunk.hpp"
#include "file_output.hpp"
#include "records.hpp"

namespace twinslam::mcap {

using namespace detail;

struct Writer::Impl {
  Impl(const std::string& path, WriterOptions opts) : options(std::move(opts)), out(path) {}

  void check_open() const {
    if (closed) throw std::logic_error("mcap: writer used after close()");
  }
  void write_message(const MessageRecord& m);
  void define_channel(std::uint16_t channel_id);
  void flush_chunk();
  void write_summary_and_footer();
  void close();

  WriterOptions options;
  FileOutput out;
  mutable std::mutex mutex;
  bool closed = false;
  std::vector<SchemaRecord> schemas;    // schemas[id - 1]
  std::vector<ChannelRecord> channels;  // channels[id - 1]
  std::vector<bool> schema_written, channel_written;
  ChunkBuilder chunk;
  std::vector<ChunkIndexRecord> chunk_indexes;
  StatisticsRecord stats;
};

// Schema and Channel go into the chunk right before the channel's first message: the spec wants each before the
// first record referring to it (spec#schema-op0x03, #channel-op0x04), and a channel that never carries a message
// then appears only in the summary.
void Writer::Impl::define_channel(std::uint16_t channel_id) {
  const ChannelRecord& channel = channels[channel_id - 1];
  if (channel.schema_id != 0 && !schema_written[channel.schema_id - 1]) {
    chunk.add_schema(schemas[channel.schema_id - 1]);
    schema_written[channel.schema_id - 1] = true;
  }
  chunk.add_channel(channel);
  channel_written[channel_id - 1] = true;
}

void Writer::Impl::write_message(const MessageRecord& m) {
  if (!channel_written[m.channel_id - 1]) define_channel(m.channel_id);
  chunk.add_message(m);
  if (stats.message_count == 0) {
    stats.message_start_time = stats.message_end_time = m.log_time;
  } else {
    stats.message_start_time = std::min(stats.message_start_time, m.log_time);
    stats.message_end_time = std::max(stats.message_end_time, m.log_time);
  }
  ++stats.message_count;
  ++stats.channel_message_counts[m.channel_id];
  if (chunk.size() >= options.chunk_size) flush_chunk();
}

// Chunk record, then its Message Index records (spec#message-index-op0x07: "immediately after each chunk"), and the
// Chunk Index that points at both for the summary (spec#chunk-index-op0x08).
void Writer::Impl::flush_chunk() {
  if (chunk.empty()) return;
  const ChunkHeader header = chunk.header();
  ChunkIndexRecord index;
  index.message_start_time = header.message_start_time;
  index.message_end_time = header.message_end_time;
  index.chunk_start_offset = out.offset();
  index.records_size = header.uncompressed_size;
  Bytes prefix;
  append_chunk_prefix(prefix, header);
  out.write(prefix);
  out.write(chunk.records());
  index.chunk_length = out.offset() - index.chunk_start_offset;
  Bytes message_indexes;
  chunk.append_message_indexes(message_indexes, out.offset(), index.message_index_offsets);
  out.write(message_indexes);
  index.message_index_length = message_indexes.size();
  chunk_indexes.push_back(std::move(index));
  chunk.clear();
}

// Summary groups in the order Schema, Channel, Statistics, Chunk Index (Channels before Statistics: spec
// #statistics-op0x0B), one Summary Offset per non-empty group (spec#summary-offset-op0x0E), then the Footer whose
// summary_crc covers everything from summary_start through its own summary_offset_start field (spec#footer-op0x02).
void Writer::Impl::write_summary_and_footer() {
  const std::uint64_t summary_start = out.offset();
  out.restart_crc();
  Bytes groups[4];
  for (const auto& s : schemas) append_schema(groups[0], s);
  for (const auto& c : channels) append_channel(groups[1], c);
  stats.schema_count = static_cast<std::uint16_t>(schemas.size());
  stats.channel_count = static_cast<std::uint32_t>(channels.size());
  stats.chunk_count = static_cast<std::uint32_t>(chunk_indexes.size());
  append_statistics(groups[2], stats);
  for (const auto& ci : chunk_indexes) append_chunk_index(groups[3], ci);
  const Op group_ops[4] = {Op::Schema, Op::Channel, Op::Statistics, Op::ChunkIndex};
  Bytes offsets;
  for (int g = 0; g < 4; ++g) {
    if (groups[g].size() == 0) continue;
    append_summary_offset(offsets, group_ops[g], out.offset(), groups[g].size());
    out.write(groups[g]);
  }
  const std::uint64_t summary_offset_start = out.offset();
  out.write(offsets);
  Bytes footer;
  append_footer_prefix(footer, summary_start, summary_offset_start);
  out.write(footer);
  Bytes tail;
  tail.u32(out.crc());
  tail.raw(kMagic.data(), kMagic.size());
  out.write(tail);
}

void Writer::Impl::close() {
  if (closed) return;
  closed = true;  // even if the disk fails below: close() is idempotent and the file is given up
  try {
    flush_chunk();
    Bytes data_end;
    append_data_end(data_end, out.crc());  // the CRC of every byte from the leading magic up to Data End
    out.write(data_end);
    write_summary_and_footer();
    out.close();
  } catch (...) {
    out.abandon();
    throw;
  }
}

Writer::Writer(const std::string& path, WriterOptions options)
    : impl_(std::make_unique<Impl>(path, std::move(options))) {
  Bytes start;
  start.raw(kMagic.data(), kMagic.size());
  append_header(start, impl_->options.profile, impl_->options.library);
  impl_->out.write(start);
  impl_->out.flush();  // a recorder learns at once that it cannot write there, not at the first full chunk
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw; close() reports errors
  }
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  const std::lock_guard lock(impl_->mutex);
  impl_->check_open();
  if (impl_->schemas.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw std::logic_error("mcap: more than 65535 schemas");
  }
  const auto id = static_cast<std::uint16_t>(impl_->schemas.size() + 1);
  impl_->schemas.push_back({id, name, encoding, data});
  impl_->schema_written.push_back(false);
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic,
                                  const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  const std::lock_guard lock(impl_->mutex);
  impl_->check_open();
  if (schema_id > impl_->schemas.size()) {
    throw std::logic_error("mcap: channel '" + topic + "' refers to unknown schema " + std::to_string(schema_id));
  }
  if (impl_->channels.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw std::logic_error("mcap: more than 65535 channels");
  }
  const auto id = static_cast<std::uint16_t>(impl_->channels.size() + 1);
  impl_->channels.push_back({id, schema_id, topic, message_encoding, metadata});
  impl_->channel_written.push_back(false);
  return id;
}

void Writer::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                   std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size) {
  const std::lock_guard lock(impl_->mutex);
  impl_->check_open();
  if (channel_id == 0 || channel_id > impl_->channels.size()) {
    throw std::logic_error("mcap: write on unknown channel " + std::to_string(channel_id));
  }
  impl_->write_message({channel_id, sequence, log_time_ns, publish_time_ns, data, size});
}

void Writer::close() {
  const std::lock_guard lock(impl_->mutex);
  impl_->close();
}

std::uint64_t Writer::message_count() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->stats.message_count;
}

}  // namespace twinslam::mcap
