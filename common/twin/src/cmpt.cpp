// cmpt splitting (3D Tiles 1.0 "Composite"). Inner tiles follow each other by their own byteLength, as CesiumJS
// reads them; their 8-byte alignment is not enforced (readers copy, they do not map).
#include "cmpt.hpp"

#include "twinslam/core/error.hpp"

namespace twinslam::twin::detail {
namespace {

std::uint32_t u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

}  // namespace

std::vector<InnerTile> split_cmpt(const std::uint8_t* d, std::size_t size, const std::string& name) {
  if (size < 16) throw InputError(where(name, 0, "cmpt header truncated (" + std::to_string(size) + " bytes)"));
  if (!(d[0] == 'c' && d[1] == 'm' && d[2] == 'p' && d[3] == 't')) throw InputError(where(name, 0, "bad cmpt magic"));
  if (u32(d + 4) != 1) {
    throw InputError(where(name, 0, "cmpt version " + std::to_string(u32(d + 4)) + " unsupported (expected 1)"));
  }
  const std::size_t byte_length = u32(d + 8);
  if (byte_length > size || byte_length < 16) {
    throw InputError(where(name, 0, "cmpt byteLength " + std::to_string(byte_length) + " does not fit the " +
                                        std::to_string(size) + " bytes available"));
  }
  const std::size_t count = u32(d + 12);
  if (count > (byte_length - 16) / 12) {  // every inner tile has at least a 12-byte header
    throw InputError(where(name, 0, "cmpt tilesLength " + std::to_string(count) + " is implausible"));
  }
  std::vector<InnerTile> tiles;
  std::size_t offset = 16;
  for (std::size_t i = 0; i < count; ++i) {
    if (byte_length - offset < 12) {
      throw InputError(where(name, 0, "cmpt inner tile " + std::to_string(i) + " header truncated"));
    }
    const std::size_t inner = u32(d + offset + 8);
    if (inner < 12 || inner > byte_length - offset) {
      throw InputError(where(name, 0, "cmpt inner tile " + std::to_string(i) + " byteLength " + std::to_string(inner) +
                                          " runs past the composite"));
    }
    tiles.push_back({offset, inner});
    offset += inner;
  }
  return tiles;
}

}  // namespace twinslam::twin::detail
