#pragma once
// A minimal MCAP reader for the tests, written from the spec (https://mcap.dev/spec) independently of the writer:
// it splits the file into `<opcode><uint64 length><content>` records, decodes the records the writer emits and keeps
// every record's file offset so the tests can check that indexes point where they say. It throws std::runtime_error
// on anything malformed (truncation, a bad magic, a record running past its parent).
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mcap_test {

using Buffer = std::vector<std::uint8_t>;
inline const Buffer kMagic{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

inline std::uint32_t zlib_crc(const std::uint8_t* p, std::size_t n) {
  return static_cast<std::uint32_t>(crc32_z(0, p, n));
}

// Little-endian reads with bounds checks over [p, p + n).
class Cursor {
 public:
  Cursor(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  std::uint64_t uint(int width) {
    need(static_cast<std::size_t>(width));
    std::uint64_t v = 0;
    for (int i = 0; i < width; ++i) v |= std::uint64_t{p_[pos_ + static_cast<std::size_t>(i)]} << (8 * i);
    pos_ += static_cast<std::size_t>(width);
    return v;
  }
  std::uint8_t u8() { return static_cast<std::uint8_t>(uint(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(uint(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(uint(4)); }
  std::uint64_t u64() { return uint(8); }
  Buffer bytes(std::size_t k) {
    need(k);
    Buffer out(p_ + pos_, p_ + pos_ + k);
    pos_ += k;
    return out;
  }
  std::string str() {
    const Buffer b = bytes(u32());
    return {b.begin(), b.end()};
  }
  std::size_t pos() const { return pos_; }
  std::size_t left() const { return n_ - pos_; }

 private:
  void need(std::size_t k) const {
    if (n_ - pos_ < k) throw std::runtime_error("mcap_test: truncated field at " + std::to_string(pos_));
  }
  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t pos_ = 0;
};

struct Record {
  std::uint8_t op = 0;
  std::uint64_t offset = 0;  // of the opcode, from the start of the file (or of the chunk records)
  std::uint64_t length = 0;  // 1 + 8 + content
  Buffer content;
  Cursor cursor() const { return {content.data(), content.size()}; }
};

// Records in [begin, end) of `p`; stops after a Footer when `stop_at_footer`.
inline std::vector<Record> split(const std::uint8_t* p, std::size_t begin, std::size_t end, bool stop_at_footer) {
  std::vector<Record> out;
  std::size_t pos = begin;
  while (pos < end) {
    Cursor c(p + pos, end - pos);
    Record r;
    r.op = c.u8();
    const std::uint64_t n = c.u64();
    r.offset = pos;
    r.content = c.bytes(n);
    r.length = 9 + n;
    pos += r.length;
    out.push_back(std::move(r));
    if (stop_at_footer && out.back().op == 0x02) break;
  }
  return out;
}

struct Schema {
  std::uint16_t id = 0;
  std::string name, encoding, data;
  bool operator==(const Schema&) const = default;
};
struct Channel {
  std::uint16_t id = 0, schema_id = 0;
  std::string topic, encoding;
  std::map<std::string, std::string> metadata;
  bool operator==(const Channel&) const = default;
};
struct Message {
  std::uint16_t channel = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0, publish_time = 0;
  Buffer data;
  bool operator==(const Message&) const = default;
};
struct Chunk {
  std::uint64_t offset = 0, length = 0;
  std::uint64_t start_time = 0, end_time = 0, uncompressed_size = 0;
  std::uint32_t crc = 0;
  std::string compression;
  Buffer records;
  std::vector<Record> inner;  // offsets relative to the start of `records`
};
struct MessageIndex {
  std::uint64_t offset = 0, length = 0;
  std::size_t chunk = 0;  // which Chunk it follows
  std::uint16_t channel = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> entries;
};
struct ChunkIndex {
  std::uint64_t start_time = 0, end_time = 0, chunk_start_offset = 0, chunk_length = 0;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0, uncompressed_size = 0;
};
struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0, attachment_count = 0, metadata_count = 0, chunk_count = 0;
  std::uint64_t start_time = 0, end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};
struct SummaryOffset {
  std::uint8_t group_op = 0;
  std::uint64_t start = 0, length = 0;
};
struct Footer {
  std::uint64_t offset = 0, summary_start = 0, summary_offset_start = 0;
  std::uint32_t summary_crc = 0;
};

struct File {
  Buffer bytes;
  std::string profile, library;
  std::vector<Record> records;  // top level, Header to Footer
  std::vector<Chunk> chunks;
  std::vector<MessageIndex> message_indexes;
  std::vector<Message> messages;                   // in file order, decoded from the chunks
  std::vector<Schema> data_schemas, summary_schemas;
  std::vector<Channel> data_channels, summary_channels;
  std::uint64_t data_end_offset = 0;
  std::uint32_t data_section_crc = 0;
  std::optional<Statistics> statistics;
  std::vector<ChunkIndex> chunk_indexes;
  std::vector<SummaryOffset> summary_offsets;
  Footer footer;
};

inline std::map<std::uint16_t, std::uint64_t> id_map(Cursor& c) {
  const std::uint32_t n = c.u32();
  const Buffer b = c.bytes(n);
  Cursor m(b.data(), b.size());
  std::map<std::uint16_t, std::uint64_t> out;
  while (m.left() > 0) {
    const std::uint16_t key = m.u16();
    out[key] = m.u64();
  }
  return out;
}

inline Schema parse_schema(const Record& r) {
  Cursor c = r.cursor();
  Schema s;
  s.id = c.u16();
  s.name = c.str();
  s.encoding = c.str();
  s.data = c.str();
  return s;
}

inline Channel parse_channel(const Record& r) {
  Cursor c = r.cursor();
  Channel ch;
  ch.id = c.u16();
  ch.schema_id = c.u16();
  ch.topic = c.str();
  ch.encoding = c.str();
  const Buffer map = c.bytes(c.u32());
  Cursor m(map.data(), map.size());
  while (m.left() > 0) {
    std::string key = m.str();
    ch.metadata[key] = m.str();
  }
  return ch;
}

inline Message parse_message(const Record& r) {
  Cursor c = r.cursor();
  Message m;
  m.channel = c.u16();
  m.sequence = c.u32();
  m.log_time = c.u64();
  m.publish_time = c.u64();
  m.data = c.bytes(c.left());
  return m;
}

inline Chunk parse_chunk(const Record& r) {
  Cursor c = r.cursor();
  Chunk ch;
  ch.offset = r.offset;
  ch.length = r.length;
  ch.start_time = c.u64();
  ch.end_time = c.u64();
  ch.uncompressed_size = c.u64();
  ch.crc = c.u32();
  ch.compression = c.str();
  ch.records = c.bytes(c.u64());
  ch.inner = split(ch.records.data(), 0, ch.records.size(), false);
  return ch;
}

inline MessageIndex parse_message_index(const Record& r, std::size_t chunk) {
  Cursor c = r.cursor();
  MessageIndex mi{r.offset, r.length, chunk, c.u16(), {}};
  const Buffer array = c.bytes(c.u32());
  Cursor a(array.data(), array.size());
  while (a.left() > 0) {
    const std::uint64_t log_time = a.u64();
    mi.entries.emplace_back(log_time, a.u64());
  }
  return mi;
}

inline ChunkIndex parse_chunk_index(const Record& r) {
  Cursor c = r.cursor();
  ChunkIndex ci;
  ci.start_time = c.u64();
  ci.end_time = c.u64();
  ci.chunk_start_offset = c.u64();
  ci.chunk_length = c.u64();
  ci.message_index_offsets = id_map(c);
  ci.message_index_length = c.u64();
  ci.compression = c.str();
  ci.compressed_size = c.u64();
  ci.uncompressed_size = c.u64();
  return ci;
}

inline Statistics parse_statistics(const Record& r) {
  Cursor c = r.cursor();
  Statistics s;
  s.message_count = c.u64();
  s.schema_count = c.u16();
  s.channel_count = c.u32();
  s.attachment_count = c.u32();
  s.metadata_count = c.u32();
  s.chunk_count = c.u32();
  s.start_time = c.u64();
  s.end_time = c.u64();
  s.channel_message_counts = id_map(c);
  return s;
}

inline void decode_chunk_records(File& f, const Chunk& chunk) {
  for (const Record& r : chunk.inner) {
    if (r.op == 0x03) f.data_schemas.push_back(parse_schema(r));
    else if (r.op == 0x04) f.data_channels.push_back(parse_channel(r));
    else if (r.op == 0x05) f.messages.push_back(parse_message(r));
    else throw std::runtime_error("mcap_test: unexpected opcode in chunk: " + std::to_string(r.op));
  }
}

inline void decode_data_record(File& f, const Record& r) {
  if (r.op == 0x06) {
    f.chunks.push_back(parse_chunk(r));
    decode_chunk_records(f, f.chunks.back());
  } else if (r.op == 0x07) {
    if (f.chunks.empty()) throw std::runtime_error("mcap_test: Message Index before any Chunk");
    f.message_indexes.push_back(parse_message_index(r, f.chunks.size() - 1));
  } else if (r.op == 0x03) {
    f.data_schemas.push_back(parse_schema(r));
  } else if (r.op == 0x04) {
    f.data_channels.push_back(parse_channel(r));
  } else {
    throw std::runtime_error("mcap_test: unexpected opcode in data section: " + std::to_string(r.op));
  }
}

inline void decode_summary_record(File& f, const Record& r) {
  if (r.op == 0x03) f.summary_schemas.push_back(parse_schema(r));
  else if (r.op == 0x04) f.summary_channels.push_back(parse_channel(r));
  else if (r.op == 0x08) f.chunk_indexes.push_back(parse_chunk_index(r));
  else if (r.op == 0x0B && f.statistics) throw std::runtime_error("mcap_test: two Statistics records");
  else if (r.op == 0x0B) f.statistics = parse_statistics(r);
  else if (r.op == 0x0E) {
    Cursor c = r.cursor();
    SummaryOffset so;
    so.group_op = c.u8();
    so.start = c.u64();
    so.length = c.u64();
    f.summary_offsets.push_back(so);
  } else {
    throw std::runtime_error("mcap_test: unexpected opcode in summary: " + std::to_string(r.op));
  }
}

inline void decode_header_and_footer(File& f) {
  const Record& header = f.records.front();
  if (header.op != 0x01) throw std::runtime_error("mcap_test: first record is not a Header");
  Cursor h = header.cursor();
  f.profile = h.str();
  f.library = h.str();
  const Record& footer = f.records.back();
  if (footer.op != 0x02 || footer.content.size() != 20) throw std::runtime_error("mcap_test: bad Footer");
  Cursor c = footer.cursor();
  f.footer = {footer.offset, c.u64(), c.u64(), c.u32()};
  if (footer.offset + footer.length + kMagic.size() != f.bytes.size()) {
    throw std::runtime_error("mcap_test: bytes between the Footer and the closing magic");
  }
}

inline File read(const std::string& path) {
  File f;
  std::ifstream in(path, std::ios::binary);
  f.bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::size_t n = f.bytes.size();
  if (n < 2 * kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), f.bytes.begin()) ||
      !std::equal(kMagic.begin(), kMagic.end(), f.bytes.end() - static_cast<std::ptrdiff_t>(kMagic.size()))) {
    throw std::runtime_error("mcap_test: missing magic");
  }
  f.records = split(f.bytes.data(), kMagic.size(), n - kMagic.size(), true);
  decode_header_and_footer(f);
  bool in_data = true;
  for (std::size_t i = 1; i + 1 < f.records.size(); ++i) {
    const Record& r = f.records[i];
    if (in_data && r.op == 0x0F) {
      in_data = false;
      f.data_end_offset = r.offset;
      f.data_section_crc = r.cursor().u32();
    } else if (in_data) {
      decode_data_record(f, r);
    } else {
      decode_summary_record(f, r);
    }
  }
  if (in_data) throw std::runtime_error("mcap_test: no Data End record");
  return f;
}

}  // namespace mcap_test
