// b3dm parsing (3D Tiles 1.0 "Batched 3D Model"); legacy header detection as CesiumJS's
// Batched3DModel3DTileContent. Every length is checked in 64-bit arithmetic before any byte is read.
#include "twinslam/twin/b3dm.hpp"

#include <cmath>
#include <limits>

#include "tile_tables.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::twin {
namespace {

std::uint32_t u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

// A table length this large is really JSON text or the glTF magic (first byte >= 0x22): see b3dm.hpp.
constexpr std::uint32_t kLegacyMarker = 0x22000000U;

struct Layout {
  int header = 28;
  std::uint64_t ft_json = 0, ft_bin = 0, bt_json = 0, bt_bin = 0;
  std::optional<std::size_t> legacy_batch_length;
};

Layout read_layout(const std::uint8_t* d, std::size_t byte_length, const std::string& name) {
  Layout l;
  if (byte_length < 20) {
    throw InputError(where(name, 0, "b3dm header truncated (" + std::to_string(byte_length) + " bytes)"));
  }
  // Words after magic / version / byteLength; a legacy-1 tile may be only 20 bytes + body, so read what exists.
  const std::uint32_t w3 = u32(d + 12);
  const std::uint32_t w4 = u32(d + 16);
  const std::uint32_t w5 = byte_length >= 24 ? u32(d + 20) : 0;
  const std::uint32_t w6 = byte_length >= 28 ? u32(d + 24) : 0;
  if (w5 >= kLegacyMarker) {  // legacy 1: [batchLength] [batchTableByteLength]
    l.header = 20;
    l.legacy_batch_length = w3;
    l.bt_json = w4;
  } else if (w6 >= kLegacyMarker) {  // legacy 2: [batchTableJSONByteLength] [batchTableBinaryByteLength] [batchLength]
    l.header = 24;
    l.bt_json = w3;
    l.bt_bin = w4;
    l.legacy_batch_length = w5;
  } else {
    if (byte_length < 28) {
      throw InputError(where(name, 0, "b3dm header truncated (" + std::to_string(byte_length) + " bytes)"));
    }
    l.ft_json = w3;
    l.ft_bin = w4;
    l.bt_json = w5;
    l.bt_bin = w6;
  }
  return l;
}

void check_aligned(std::uint64_t offset, const char* what, const std::string& name) {
  if (offset % 8 != 0) {
    throw InputError(where(name, 0, std::string("b3dm ") + what + " starts at byte " + std::to_string(offset) +
                                        ", not on an 8-byte boundary"));
  }
}

B3dmContent parse_checked(const std::uint8_t* d, std::size_t size, const std::string& name, B3dmCheck check) {
  if (d == nullptr || size < 12) {
    throw InputError(where(name, 0, "b3dm header truncated (" + std::to_string(size) + " bytes)"));
  }
  if (!(d[0] == 'b' && d[1] == '3' && d[2] == 'd' && d[3] == 'm')) {
    throw InputError(where(name, 0, "bad b3dm magic (expected 'b3dm')"));
  }
  const std::uint32_t version = u32(d + 4);
  if (version != 1) {
    throw InputError(where(name, 0, "b3dm version " + std::to_string(version) + " unsupported (expected 1)"));
  }
  const std::size_t byte_length = u32(d + 8);
  if (byte_length > size) {
    throw InputError(where(name, 0, "b3dm byteLength " + std::to_string(byte_length) + " exceeds the " +
                                        std::to_string(size) + " bytes available (truncated)"));
  }
  const Layout l = read_layout(d, byte_length, name);
  const bool legacy = l.legacy_batch_length.has_value();
  if (check == B3dmCheck::kStrict && byte_length % 8 != 0) {
    throw InputError(where(name, 0, "b3dm byteLength " + std::to_string(byte_length) + " is not a multiple of 8"));
  }
  const std::uint64_t ft_json_at = static_cast<std::uint64_t>(l.header);
  const std::uint64_t ft_bin_at = ft_json_at + l.ft_json;
  const std::uint64_t bt_json_at = ft_bin_at + l.ft_bin;
  const std::uint64_t bt_bin_at = bt_json_at + l.bt_json;
  const std::uint64_t glb_at = bt_bin_at + l.bt_bin;
  if (glb_at > byte_length) {
    const std::uint64_t tables = glb_at - static_cast<std::uint64_t>(l.header);
    throw InputError(where(name, 0, "b3dm table lengths (" + std::to_string(tables) +
                                        " bytes) run past byteLength " + std::to_string(byte_length)));
  }
  if (!legacy) {  // the legacy layouts predate the padding rules
    check_aligned(ft_bin_at, "feature table binary", name);
    check_aligned(bt_json_at, "batch table JSON", name);
    check_aligned(bt_bin_at, "batch table binary", name);
    check_aligned(glb_at, "glb", name);
  }
  const detail::TableBytes ft{d + ft_json_at, l.ft_json, d + ft_bin_at, l.ft_bin};
  const detail::TableBytes bt{d + bt_json_at, l.bt_json, d + bt_bin_at, l.bt_bin};

  B3dmContent out;
  out.header_bytes = l.header;
  out.unpadded = byte_length % 8 != 0;
  std::size_t batch_length = l.legacy_batch_length.value_or(0);
  const nlohmann::json fj = detail::parse_table_json(ft, name, "feature table");
  if (!legacy) {
    if (!fj.contains("BATCH_LENGTH") || !fj["BATCH_LENGTH"].is_number_unsigned()) {
      throw InputError(where(name, 0, "feature table lacks a non-negative integer BATCH_LENGTH"));
    }
    batch_length = fj["BATCH_LENGTH"].get<std::size_t>();
  }
  if (batch_length > byte_length) {  // every feature needs at least one vertex byte: anything larger is garbage
    throw InputError(where(name, 0, "BATCH_LENGTH " + std::to_string(batch_length) + " is implausible"));
  }
  if (fj.contains("RTC_CENTER")) {
    const std::vector<double> c = detail::table_numbers(ft, fj["RTC_CENTER"], 1, 3, "FLOAT", name, "RTC_CENTER");
    out.rtc_center = Eigen::Vector3d(c[0], c[1], c[2]);
    if (!out.rtc_center->allFinite()) throw InputError(where(name, 0, "RTC_CENTER is not finite"));
  }
  out.batch_table = detail::parse_batch_table(bt, batch_length, name);

  const std::size_t glb_size = byte_length - static_cast<std::size_t>(glb_at);
  if (glb_size == 0) throw InputError(where(name, 0, "b3dm holds no glb"));
  out.gltf = load_gltf_content(d + glb_at, glb_size, name + " (glb)");
  for (std::uint32_t id : out.gltf.batch_id) {
    if (id >= batch_length && id != std::numeric_limits<std::uint32_t>::max()) {
      throw InputError(where(name, 0, "vertex batch id " + std::to_string(id) + " >= BATCH_LENGTH " +
                                          std::to_string(batch_length)));
    }
  }
  return out;
}

}  // namespace

B3dmContent parse_b3dm(const std::uint8_t* d, std::size_t size, const std::string& name, B3dmCheck check) {
  try {
    return parse_checked(d, size, name, check);
  } catch (const nlohmann::json::exception& e) {  // a table value of an unexpected JSON type
    throw InputError(where(name, 0, std::string("b3dm table JSON: ") + e.what()));
  }
}

B3dmContent load_b3dm_file(const std::string& path, B3dmCheck check) {
  const std::vector<std::uint8_t> bytes = read_binary_file(path);
  return parse_b3dm(bytes.data(), bytes.size(), path, check);
}

}  // namespace twinslam::twin
