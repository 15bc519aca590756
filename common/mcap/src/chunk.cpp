#include "chunk.hpp"

#include <algorithm>

namespace twinslam::mcap::detail {

void ChunkBuilder::add_message(const MessageRecord& r) {
  // Messages arrive from several DDS threads, so log times need not grow: keep the extremes.
  if (index_.empty()) {
    start_time_ = end_time_ = r.log_time;
  } else {
    start_time_ = std::min(start_time_, r.log_time);
    end_time_ = std::max(end_time_, r.log_time);
  }
  index_[r.channel_id].emplace_back(r.log_time, records_.size());
  append_message(records_, r);
}

ChunkHeader ChunkBuilder::header() const {
  ChunkHeader h;
  h.message_start_time = start_time_;
  h.message_end_time = end_time_;
  h.uncompressed_size = records_.size();
  h.uncompressed_crc = crc32(0, records_.data(), records_.size());
  return h;
}

void ChunkBuilder::append_message_indexes(Bytes& out, std::uint64_t first,
                                          std::map<std::uint16_t, std::uint64_t>& offsets) const {
  const std::size_t base = out.size();
  for (const auto& [channel_id, entries] : index_) {
    offsets[channel_id] = first + (out.size() - base);
    // Sorted by log time (then offset) so a reader may binary-search a channel's messages within the chunk.
    IndexEntries sorted = entries;
    std::sort(sorted.begin(), sorted.end());
    append_message_index(out, channel_id, sorted);
  }
}

void ChunkBuilder::clear() {
  records_.clear();
  index_.clear();
  start_time_ = end_time_ = 0;
}

}  // namespace twinslam::mcap::detail
