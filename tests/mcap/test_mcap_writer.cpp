// twinslam_mcap's Writer read back by the test's own spec reader (mcap_test_reader.hpp): every message comes back,
// every index and offset points at the record it names, the CRCs match zlib's, across several chunks and channels,
// from several threads, and for a file without messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>
#include <thread>

#include "mcap_test_reader.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/mcap/writer.hpp"

namespace {

using namespace mcap_test;
namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("twinslam_mcap_" + name + "_" + std::to_string(getpid()) + ".mcap")).string();
}

// Deterministic payload bytes of one message.
Buffer payload(std::uint16_t channel, std::uint32_t sequence, std::size_t size) {
  Buffer b(size);
  for (std::size_t i = 0; i < size; ++i) b[i] = static_cast<std::uint8_t>(channel * 31 + sequence * 7 + i);
  return b;
}

void write(twinslam::mcap::Writer& w, const Message& m) {
  w.write(m.channel, m.sequence, m.log_time, m.publish_time, m.data.data(), m.data.size());
}

const Record* record_at(const File& f, std::uint64_t offset) {
  for (const Record& r : f.records) {
    if (r.offset == offset) return &r;
  }
  return nullptr;
}

// --- structural checks shared by every file the tests write --------------------------------------------------

void expect_chunks_valid(const File& f) {
  std::size_t next_message = 0;
  for (const Chunk& c : f.chunks) {
    EXPECT_EQ(c.compression, "");
    EXPECT_EQ(c.uncompressed_size, c.records.size());
    EXPECT_EQ(c.crc, zlib_crc(c.records.data(), c.records.size()));
    std::uint64_t lo = UINT64_MAX, hi = 0;
    for (const Record& r : c.inner) {
      if (r.op != 0x05) continue;
      const Message& m = f.messages.at(next_message++);
      lo = std::min(lo, m.log_time);
      hi = std::max(hi, m.log_time);
    }
    ASSERT_LE(lo, hi) << "a chunk without messages at " << c.offset;
    EXPECT_EQ(c.start_time, lo);
    EXPECT_EQ(c.end_time, hi);
  }
}

// Each chunk is followed directly by one Message Index per channel it holds, whose entries are exactly its messages.
void expect_message_indexes_valid(const File& f) {
  std::vector<std::size_t> entries_per_chunk(f.chunks.size(), 0);
  std::vector<std::set<std::uint16_t>> channels_per_chunk(f.chunks.size());
  for (std::size_t i = 0; i < f.message_indexes.size(); ++i) {
    const MessageIndex& mi = f.message_indexes[i];
    const Chunk& c = f.chunks[mi.chunk];
    const bool first = i == 0 || f.message_indexes[i - 1].chunk != mi.chunk;
    const std::uint64_t expected = first ? c.offset + c.length
                                         : f.message_indexes[i - 1].offset + f.message_indexes[i - 1].length;
    EXPECT_EQ(mi.offset, expected) << "Message Index records follow their chunk without a gap";
    EXPECT_TRUE(channels_per_chunk[mi.chunk].insert(mi.channel).second) << "one Message Index per channel";
    for (const auto& entry : mi.entries) {
      const auto& [log_time, offset] = entry;
      // entry.second, not the binding: clang 14 (the sanitized tree's compiler) cannot capture structured bindings.
      const auto it =
          std::find_if(c.inner.begin(), c.inner.end(), [&](const Record& r) { return r.offset == entry.second; });
      ASSERT_NE(it, c.inner.end()) << "entry offset " << offset << " is no record of the chunk";
      ASSERT_EQ(it->op, 0x05);
      const Message m = parse_message(*it);
      EXPECT_EQ(m.channel, mi.channel);
      EXPECT_EQ(m.log_time, log_time);
    }
    entries_per_chunk[mi.chunk] += mi.entries.size();
  }
  for (std::size_t k = 0; k < f.chunks.size(); ++k) {
    const auto n = std::count_if(f.chunks[k].inner.begin(), f.chunks[k].inner.end(),
                                 [](const Record& r) { return r.op == 0x05; });
    EXPECT_EQ(entries_per_chunk[k], static_cast<std::size_t>(n)) << "chunk " << k;
  }
}

void expect_chunk_indexes_valid(const File& f) {
  ASSERT_EQ(f.chunk_indexes.size(), f.chunks.size());
  for (std::size_t k = 0; k < f.chunks.size(); ++k) {
    const ChunkIndex& ci = f.chunk_indexes[k];
    const Chunk& c = f.chunks[k];
    EXPECT_EQ(ci.chunk_start_offset, c.offset);
    EXPECT_EQ(ci.chunk_length, c.length);
    EXPECT_EQ(ci.start_time, c.start_time);
    EXPECT_EQ(ci.end_time, c.end_time);
    EXPECT_EQ(ci.compression, "");
    EXPECT_EQ(ci.compressed_size, c.records.size());
    EXPECT_EQ(ci.uncompressed_size, c.records.size());
    std::map<std::uint16_t, std::uint64_t> offsets;
    std::uint64_t length = 0;
    for (const MessageIndex& mi : f.message_indexes) {
      if (mi.chunk != k) continue;
      offsets[mi.channel] = mi.offset;
      length += mi.length;
    }
    EXPECT_EQ(ci.message_index_offsets, offsets);
    EXPECT_EQ(ci.message_index_length, length);
  }
}

// Summary Offsets name contiguous single-opcode groups that tile the summary; the Footer points at both sections.
void expect_summary_offsets_and_footer_valid(const File& f) {
  const Record* data_end = record_at(f, f.data_end_offset);
  ASSERT_NE(data_end, nullptr);
  EXPECT_EQ(f.footer.summary_start, data_end->offset + data_end->length);
  std::uint64_t pos = f.footer.summary_start;
  for (const SummaryOffset& so : f.summary_offsets) {
    EXPECT_EQ(so.start, pos) << "groups are contiguous, in Summary Offset order";
    for (std::uint64_t at = so.start; at < so.start + so.length;) {
      const Record* r = record_at(f, at);
      ASSERT_NE(r, nullptr) << "group 0x" << std::hex << int{so.group_op} << " has no record at " << std::dec << at;
      EXPECT_EQ(r->op, so.group_op);
      at += r->length;
      EXPECT_LE(at, so.start + so.length);
    }
    pos = so.start + so.length;
  }
  EXPECT_EQ(pos, f.footer.summary_offset_start) << "the groups cover the whole summary";
  const Record* first_offset = record_at(f, f.footer.summary_offset_start);
  ASSERT_NE(first_offset, nullptr);
  EXPECT_EQ(first_offset->op, 0x0E);
  std::size_t n = 0;
  for (const Record& r : f.records) n += r.op == 0x0E && r.offset >= f.footer.summary_offset_start ? 1 : 0;
  EXPECT_EQ(n, f.summary_offsets.size());
}

void expect_crcs_valid(const File& f) {
  EXPECT_EQ(f.data_section_crc, zlib_crc(f.bytes.data(), f.data_end_offset));
  // From summary_start through the Footer's summary_offset_start field (opcode 1 + length 8 + two uint64).
  const std::uint64_t end = f.footer.offset + 1 + 8 + 8 + 8;
  EXPECT_EQ(f.footer.summary_crc, zlib_crc(f.bytes.data() + f.footer.summary_start, end - f.footer.summary_start));
}

void expect_valid(const File& f) {
  expect_chunks_valid(f);
  expect_message_indexes_valid(f);
  expect_chunk_indexes_valid(f);
  expect_summary_offsets_and_footer_valid(f);
  expect_crcs_valid(f);
}

// --- a file of 3 schemas, 4 channels (one never used, one without schema), many small chunks ---------------------

class McapWriterFile : public ::testing::Test {
 protected:
  static constexpr std::size_t kChunkSize = 700;

  static void SetUpTestSuite() {
    path_ = temp_path("file");
    schemas_ = {{1, "m::Imu", "omgidl", "module m { struct Imu { double t; }; };"},
                {2, "m::Image", "omgidl", "module m { struct Image { sequence<octet> data; }; };"},
                {3, "m::Unused", "omgidl", "module m { struct Unused { long x; }; };"}};
    channels_ = {{1, 1, "/imu", "cdr", {{"offered_qos_profiles", "reliable"}}},
                 {2, 2, "/image", "cdr", {}},
                 {3, 0, "/raw", "cdr", {}},
                 {4, 3, "/unused", "cdr", {}}};
    twinslam::mcap::Writer w(path_, {.profile = "", .library = "twinslam-test", .chunk_size = kChunkSize});
    for (const Schema& s : schemas_) ASSERT_EQ(w.add_schema(s.name, s.encoding, s.data), s.id);
    for (const Channel& c : channels_) ASSERT_EQ(w.add_channel(c.schema_id, c.topic, c.encoding, c.metadata), c.id);
    for (std::uint32_t i = 0; i < 300; ++i) {
      const auto channel = static_cast<std::uint16_t>(1 + i % 3);
      // Every 5th message late (as from several DDS threads), so neither the file's nor most chunks' first
      // message is the earliest: the writer must keep the extremes, not the first and last.
      const std::uint64_t log_time = 1'000'000'000 + i * 1000 + (i % 5 == 0 ? 6000 : 0);
      written_.push_back({channel, i / 3, log_time, log_time - 250, payload(channel, i, (i * 37) % 160)});
      write(w, written_.back());
    }
    EXPECT_EQ(w.message_count(), 300u);
    w.close();
    file_ = std::make_unique<File>(read(path_));
  }
  static void TearDownTestSuite() {
    file_.reset();
    fs::remove(path_);
  }

  static inline std::string path_;
  static inline std::vector<Schema> schemas_;
  static inline std::vector<Channel> channels_;
  static inline std::vector<Message> written_;
  static inline std::unique_ptr<File> file_;
};

TEST_F(McapWriterFile, MagicAtBothEndsAndTheHeaderNamesTheLibrary) {
  const Buffer& b = file_->bytes;
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), b.begin()));
  EXPECT_TRUE(std::equal(kMagic.rbegin(), kMagic.rend(), b.rbegin()));
  EXPECT_EQ(file_->profile, "");
  EXPECT_EQ(file_->library, "twinslam-test");
}

TEST_F(McapWriterFile, EveryMessageComesBackWithItsChannelSequenceTimesAndBytes) {
  EXPECT_GE(file_->chunks.size(), 10u) << "the test needs several chunks";
  ASSERT_EQ(file_->messages.size(), written_.size());
  for (std::size_t i = 0; i < written_.size(); ++i) EXPECT_EQ(file_->messages[i], written_[i]) << "message " << i;
}

TEST_F(McapWriterFile, ChunksAreUncompressedWithTheirCrcSizeAndTimeRange) {
  expect_chunks_valid(*file_);
  for (std::size_t k = 0; k + 1 < file_->chunks.size(); ++k) {
    EXPECT_GE(file_->chunks[k].records.size(), kChunkSize) << "a chunk is closed once it reaches chunk_size";
  }
}

TEST_F(McapWriterFile, MessageIndexesFollowTheirChunkAndPointAtItsMessages) {
  expect_message_indexes_valid(*file_);
}

TEST_F(McapWriterFile, ChunkIndexesPointAtTheChunksAndTheirMessageIndexes) { expect_chunk_indexes_valid(*file_); }

TEST_F(McapWriterFile, SummaryOffsetsAndFooterPointAtTheirRecords) {
  expect_summary_offsets_and_footer_valid(*file_);
  std::vector<std::uint8_t> groups;
  for (const SummaryOffset& so : file_->summary_offsets) groups.push_back(so.group_op);
  EXPECT_EQ(groups, (std::vector<std::uint8_t>{0x03, 0x04, 0x0B, 0x08}));  // Schema, Channel, Statistics, ChunkIndex
}

TEST_F(McapWriterFile, DataSectionAndSummaryCrcsMatchZlib) { expect_crcs_valid(*file_); }

TEST_F(McapWriterFile, SchemasAndChannelsPrecedeTheirFirstMessageAndAreRepeatedInTheSummary) {
  EXPECT_EQ(file_->summary_schemas, schemas_);
  EXPECT_EQ(file_->summary_channels, channels_);
  // In the data section: each used schema and channel once, the schema before its channel; the unused ones not.
  EXPECT_EQ(file_->data_schemas, (std::vector<Schema>{schemas_[0], schemas_[1]}));
  EXPECT_EQ(file_->data_channels, (std::vector<Channel>{channels_[0], channels_[1], channels_[2]}));
  const Chunk& first = file_->chunks.front();
  std::vector<std::uint8_t> ops;
  for (const Record& r : first.inner) ops.push_back(r.op);
  ASSERT_GE(ops.size(), 8u);
  // Schema 1, Channel 1, Message 1, Schema 2, Channel 2, Message 2, Channel 3 (no schema), Message 3.
  EXPECT_EQ(std::vector<std::uint8_t>(ops.begin(), ops.begin() + 8),
            (std::vector<std::uint8_t>{0x03, 0x04, 0x05, 0x03, 0x04, 0x05, 0x04, 0x05}));
}

TEST_F(McapWriterFile, StatisticsCountEverything) {
  ASSERT_TRUE(file_->statistics.has_value());
  const Statistics& s = *file_->statistics;
  EXPECT_EQ(s.message_count, written_.size());
  EXPECT_EQ(s.schema_count, 3);
  EXPECT_EQ(s.channel_count, 4u);
  EXPECT_EQ(s.attachment_count, 0u);
  EXPECT_EQ(s.metadata_count, 0u);
  EXPECT_EQ(s.chunk_count, file_->chunks.size());
  std::uint64_t lo = UINT64_MAX, hi = 0;
  std::map<std::uint16_t, std::uint64_t> counts;
  for (const Message& m : written_) {
    lo = std::min(lo, m.log_time);
    hi = std::max(hi, m.log_time);
    ++counts[m.channel];
  }
  EXPECT_EQ(s.start_time, lo);
  EXPECT_EQ(s.end_time, hi);
  EXPECT_EQ(s.channel_message_counts, counts);
}

// --- edge cases ---------------------------------------------------------------------------------------------------

TEST(McapWriter, AFileWithoutMessagesIsStillValid) {
  const std::string path = temp_path("empty");
  twinslam::mcap::Writer(path).close();
  const File f = read(path);
  std::vector<std::uint8_t> ops;
  for (const Record& r : f.records) ops.push_back(r.op);
  EXPECT_EQ(ops, (std::vector<std::uint8_t>{0x01, 0x0F, 0x0B, 0x0E, 0x02}));  // Header DataEnd Statistics Offset Footer
  ASSERT_TRUE(f.statistics.has_value());
  EXPECT_EQ(f.statistics->message_count, 0u);
  EXPECT_EQ(f.statistics->chunk_count, 0u);
  EXPECT_EQ(f.statistics->start_time, 0u);
  EXPECT_TRUE(f.statistics->channel_message_counts.empty());
  expect_valid(f);
  fs::remove(path);
}

TEST(McapWriter, ChannelsWithoutMessagesAreOnlyInTheSummary) {
  const std::string path = temp_path("idle");
  {
    twinslam::mcap::Writer w(path);
    w.add_channel(w.add_schema("m::A", "omgidl", "module m { struct A { long x; }; };"), "/a", "cdr");
  }  // the destructor closes
  const File f = read(path);
  EXPECT_TRUE(f.chunks.empty());
  EXPECT_TRUE(f.data_channels.empty());
  ASSERT_EQ(f.summary_channels.size(), 1u);
  EXPECT_EQ(f.summary_channels[0].topic, "/a");
  EXPECT_EQ(f.statistics->schema_count, 1);
  EXPECT_EQ(f.statistics->channel_count, 1u);
  expect_valid(f);
  fs::remove(path);
}

TEST(McapWriter, APathInAMissingDirectoryThrowsInputErrorNamingThePath) {
  const std::string path = (fs::temp_directory_path() / "twinslam_no_such_dir" / "x.mcap").string();
  try {
    twinslam::mcap::Writer w(path);
    FAIL() << "no error";
  } catch (const twinslam::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": cannot write"), std::string::npos) << e.what();
  }
}

TEST(McapWriter, AFullDiskThrowsInputErrorNamingThePath) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  try {
    twinslam::mcap::Writer w("/dev/full");
    w.close();
    FAIL() << "no error";
  } catch (const twinslam::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full: cannot write"), std::string::npos) << e.what();
  }
}

TEST(McapWriter, MisuseThrowsLogicErrorAndWritesNothing) {
  const std::string path = temp_path("misuse");
  twinslam::mcap::Writer w(path);
  const std::uint16_t channel = w.add_channel(0, "/a", "cdr");
  const std::uint8_t byte = 1;
  EXPECT_THROW(w.write(0, 0, 1, 1, &byte, 1), std::logic_error);
  EXPECT_THROW(w.write(channel + 1, 0, 1, 1, &byte, 1), std::logic_error);
  EXPECT_THROW(w.add_channel(7, "/b", "cdr"), std::logic_error) << "unknown schema";
  EXPECT_EQ(w.message_count(), 0u);
  w.close();
  EXPECT_NO_THROW(w.close()) << "close() is idempotent";
  EXPECT_THROW(w.write(channel, 0, 1, 1, &byte, 1), std::logic_error) << "write after close";
  const File f = read(path);
  EXPECT_TRUE(f.messages.empty());
  expect_valid(f);
  fs::remove(path);
}

TEST(McapWriter, FourThreadsWritingAtOnceLoseNoMessage) {
  const std::string path = temp_path("threads");
  constexpr std::uint32_t kPerThread = 1500;
  twinslam::mcap::WriterOptions options;
  options.chunk_size = 4096;
  twinslam::mcap::Writer w(path, options);
  const std::uint16_t schema = w.add_schema("m::A", "omgidl", "module m { struct A { long x; }; };");
  std::vector<std::thread> threads;
  for (std::uint16_t t = 0; t < 4; ++t) {
    const std::uint16_t channel = w.add_channel(schema, "/t" + std::to_string(t), "cdr");
    threads.emplace_back([&w, channel] {
      for (std::uint32_t seq = 0; seq < kPerThread; ++seq) {
        const Buffer data = payload(channel, seq, 8 + seq % 50);
        w.write(channel, seq, 1000ull * seq + channel, 1000ull * seq, data.data(), data.size());
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(w.message_count(), 4u * kPerThread);
  w.close();
  const File f = read(path);
  expect_valid(f);
  std::map<std::uint16_t, std::set<std::uint32_t>> seen;
  for (const Message& m : f.messages) {
    EXPECT_EQ(m.data, payload(m.channel, m.sequence, 8 + m.sequence % 50));
    EXPECT_TRUE(seen[m.channel].insert(m.sequence).second) << "duplicate " << m.channel << "/" << m.sequence;
  }
  ASSERT_EQ(seen.size(), 4u);
  for (const auto& [channel, sequences] : seen) EXPECT_EQ(sequences.size(), kPerThread) << "channel " << channel;
  EXPECT_EQ(f.statistics->message_count, 4u * kPerThread);
  fs::remove(path);
}

}  // namespace
