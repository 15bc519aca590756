#pragma once
// Private: the Composite (cmpt) tile format of 3D Tiles 1.0: a 16-byte header (magic "cmpt", version 1, byteLength,
// tilesLength) followed by tilesLength inner tiles, each starting with magic / version / byteLength.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace twinslam::twin::detail {

struct InnerTile {
  std::size_t offset = 0;  // from the cmpt start
  std::size_t size = 0;    // the inner tile's byteLength
};

// Inner tiles in file order; throws InputError naming `name` when a length runs past the end.
std::vector<InnerTile> split_cmpt(const std::uint8_t* data, std::size_t size, const std::string& name);

}  // namespace twinslam::twin::detail
