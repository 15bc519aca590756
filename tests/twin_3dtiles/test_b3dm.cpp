// b3dm: the validator's valid / invalid samples, legacy headers, feature and batch tables, truncation.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "tiles_test_utils.hpp"
#include "twinslam/twin/b3dm.hpp"

using namespace twinslam::twin;
using namespace tiles_test;

namespace {
B3dmContent parse(const std::vector<std::uint8_t>& b, B3dmCheck check = B3dmCheck::kLenient) {
  return parse_b3dm(b.data(), b.size(), "tile.b3dm", check);
}
}  // namespace

TEST(B3dm, ValidSampleHasItsTablesAndBatchIds) {
  const B3dmContent c = load_b3dm_file(sample("cesium-validator/valid.b3dm"), B3dmCheck::kStrict);
  EXPECT_EQ(c.header_bytes, 28);
  ASSERT_TRUE(c.rtc_center.has_value());
  EXPECT_NEAR(c.rtc_center->x(), 1215019.2111447915, 1e-6);
  EXPECT_EQ(c.batch_table.batch_length, 10u);
  ASSERT_NE(c.batch_table.find("Height"), nullptr);
  EXPECT_EQ(c.batch_table.find("Height")->size(), 10u);
  EXPECT_GT(c.gltf.mesh.num_triangles(), 0u);
  ASSERT_EQ(c.gltf.batch_id.size(), c.gltf.mesh.num_vertices());
  std::set<std::uint32_t> ids(c.gltf.batch_id.begin(), c.gltf.batch_id.end());
  EXPECT_EQ(ids.size(), 10u);  // ten buildings, each with vertices
}

TEST(B3dm, InvalidValidatorSamplesAreRejectedWithTheReason) {
  const std::string dir = sample("cesium-validator/");
  expect_input_error([&] { load_b3dm_file(dir + "invalid.b3dm"); }, {"invalid.b3dm", "version 2"});
  expect_input_error([&] { load_b3dm_file(dir + "validWithInvalidGlb.b3dm"); },
                     {"validWithInvalidGlb.b3dm", "GLB length 13296 exceeds"});
  expect_input_error([&] { load_b3dm_file(dir + "invalidDueToWrongAlignmentWithGlbWithInfos.b3dm"); },
                     {"invalidDueToWrongAlignmentWithGlbWithInfos.b3dm", "feature table binary starts at byte 49"});
  // invalidAlignment.b3dm breaks only the whole-tile padding rule (byteLength 13316 % 8 != 0): the strict check
  // rejects it. The same rule is broken by the 2017 sample city tiles (ll.b3dm: 9700 bytes), which CesiumJS draws,
  // so the lenient check (the tileset loader's) accepts both; the strict one rejects both.
  expect_input_error([&] { load_b3dm_file(dir + "invalidAlignment.b3dm", B3dmCheck::kStrict); },
                     {"invalidAlignment.b3dm", "byteLength 13316 is not a multiple of 8"});
  const std::string ll = sample("cesium-samples/TilesetWithRequestVolume/city/ll.b3dm");
  expect_input_error([&] { load_b3dm_file(ll, B3dmCheck::kStrict); }, {"ll.b3dm", "not a multiple of 8"});
  EXPECT_GT(load_b3dm_file(ll).gltf.mesh.num_triangles(), 0u);
}

TEST(B3dm, LegacyHeadersLoadLikeTheCurrentOne) {
  // Legacy 1 (20-byte header): the sample from 3d-tiles-tools.
  const B3dmContent legacy1 = load_b3dm_file(sample("cesium-tools/Batched/BatchedDeprecated1/batchedDeprecated1.b3dm"));
  EXPECT_EQ(legacy1.header_bytes, 20);
  EXPECT_EQ(legacy1.batch_table.batch_length, 10u);
  ASSERT_NE(legacy1.batch_table.find("Longitude"), nullptr);
  EXPECT_EQ(legacy1.gltf.batch_id.size(), legacy1.gltf.mesh.num_vertices());  // legacy "BATCHID" attribute

  // Legacy 2 (24-byte header) rebuilt from the current-format WGS84 tile: its feature table only says
  // BATCH_LENGTH 10, which moves into the header.
  const std::vector<std::uint8_t> cur = bytes_of(sample("cesium-tools/Batched/BatchedWGS84/batchedWGS84.b3dm"));
  const std::uint32_t ft_json = get_u32(cur, 12), bt_json = get_u32(cur, 20);
  std::vector<std::uint8_t> old(24);
  std::copy(cur.begin(), cur.begin() + 12, old.begin());
  put_u32(old, 12, bt_json);
  put_u32(old, 16, 0);
  put_u32(old, 20, 10);
  old.insert(old.end(), cur.begin() + 28 + ft_json, cur.end());
  put_u32(old, 8, static_cast<std::uint32_t>(old.size()));
  const B3dmContent legacy2 = parse(old);
  const B3dmContent current = parse(cur);
  EXPECT_EQ(legacy2.header_bytes, 24);
  EXPECT_EQ(legacy2.batch_table.batch_length, 10u);
  EXPECT_EQ(legacy2.batch_table.numbers, current.batch_table.numbers);
  EXPECT_EQ(legacy2.gltf.mesh.p_W, current.gltf.mesh.p_W);
}

TEST(B3dm, TruncatedOrCorruptedBytesThrowNeverCrash) {
  const std::vector<std::uint8_t> valid = bytes_of(sample("cesium-validator/valid.b3dm"));
  expect_input_error([&] { parse({valid.begin(), valid.begin() + 9}); }, {"tile.b3dm", "header truncated"});
  std::vector<std::uint8_t> magic = valid;
  magic[0] = 'x';
  expect_input_error([&] { parse(magic); }, {"tile.b3dm", "bad b3dm magic"});
  std::vector<std::uint8_t> tables = valid;
  put_u32(tables, 20, 1u << 20);  // batch table JSON length past the end
  expect_input_error([&] { parse(tables); }, {"tile.b3dm", "run past byteLength"});
  std::vector<std::uint8_t> ft = valid;
  ft[28] = '[';  // feature table JSON no longer an object
  expect_input_error([&] { parse(ft); }, {"tile.b3dm", "feature table JSON"});
  // Cut anywhere (byteLength patched to match, as a writer that lost data would): always InputError or a mesh.
  for (std::size_t cut = 0; cut < valid.size(); cut += 97) {
    std::vector<std::uint8_t> b(valid.begin(), valid.begin() + static_cast<long>(cut));
    if (b.size() >= 12) put_u32(b, 8, static_cast<std::uint32_t>(b.size()));
    try {
      parse(b);
    } catch (const twinslam::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("tile.b3dm"), std::string::npos) << e.what();
    }
  }
  // A plain cut (byteLength still the original): truncation named as such.
  expect_input_error([&] { parse({valid.begin(), valid.end() - 100}); }, {"tile.b3dm", "truncated"});
}

TEST(B3dm, RandomByteCorruptionNeverCrashes) {
  // Byte flips in the header, the tables, the glb's JSON and its binary chunk: every parse ends in a mesh (whose
  // indices are valid) or an InputError naming the file, never in a crash or another exception.
  const std::vector<std::uint8_t> valid = bytes_of(sample("cesium-validator/valid.b3dm"));
  std::mt19937 rng(11);
  int errors = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::vector<std::uint8_t> b = valid;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) {
      // Half the flips hit the text parts (header, tables, glTF JSON: the first ~2.2 kB), where structure lives.
      const std::size_t at = rng() % 2 == 0 ? rng() % 2200 : rng() % b.size();
      b[at] = static_cast<std::uint8_t>(rng());
    }
    try {
      const B3dmContent c = parse(b);
      const auto n = static_cast<int>(c.gltf.mesh.num_vertices());
      for (const Eigen::Vector3i& t : c.gltf.mesh.triangles) {
        ASSERT_TRUE((t.array() >= 0).all() && (t.array() < n).all());
      }
    } catch (const twinslam::InputError& e) {
      ++errors;
      ASSERT_NE(std::string(e.what()).find("tile.b3dm"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(errors, 100);
}
