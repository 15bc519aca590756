#pragma once
// Private: the GLB container (glTF 2.0 binary): 12-byte header (magic "glTF", version 2, length), then chunks of
// (length, type, data): the first must be JSON, an optional BIN follows; unknown chunk types are skipped (spec).
// Checked here before tinygltf sees the bytes, so the reasons are precise and nothing is read out of range.
#include <cstddef>
#include <cstdint>
#include <string>

namespace twinslam::twin::detail {

struct GlbChunks {
  std::size_t length = 0;        // glTF length field: the GLB's bytes (may be < the given size: padding follows)
  std::size_t json_offset = 0;   // of the JSON chunk data, from the GLB start
  std::size_t json_size = 0;
  std::size_t bin_offset = 0;    // of the BIN chunk data (0 when there is none)
  std::size_t bin_size = 0;
};

inline bool looks_like_glb(const std::uint8_t* data, std::size_t size) {
  return size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
}

// Throws InputError naming `name` and the problem.
GlbChunks check_glb(const std::uint8_t* data, std::size_t size, const std::string& name);

}  // namespace twinslam::twin::detail
