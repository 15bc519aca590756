// GLB container checks (glTF 2.0 spec, "Binary glTF Layout").
#include "glb.hpp"

#include <cstring>

#include "twinslam/core/error.hpp"

namespace twinslam::twin::detail {
namespace {

std::uint32_t u32(const std::uint8_t* p) {
  // Little-endian on disk; assembled bytewise so the host byte order and alignment do not matter.
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

constexpr std::uint32_t kJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBin = 0x004E4942;   // "BIN\0"

}  // namespace

GlbChunks check_glb(const std::uint8_t* data, std::size_t size, const std::string& name) {
  if (size < 12) {
    throw InputError(where(name, 0, "GLB shorter than its 12-byte header (" + std::to_string(size) + " bytes)"));
  }
  if (!looks_like_glb(data, size)) throw InputError(where(name, 0, "bad GLB magic (expected 'glTF')"));
  const std::uint32_t version = u32(data + 4);
  if (version != 2) {
    throw InputError(where(name, 0, "GLB version " + std::to_string(version) + " unsupported (only glTF 2.0)"));
  }
  GlbChunks out;
  out.length = u32(data + 8);
  if (out.length > size) {
    throw InputError(where(name, 0, "GLB length " + std::to_string(out.length) + " exceeds the " +
                                        std::to_string(size) + " bytes available"));
  }
  std::size_t offset = 12;
  int index = 0;
  while (offset < out.length) {
    if (out.length - offset < 8) {
      throw InputError(where(name, 0, "GLB chunk " + std::to_string(index) + " header truncated"));
    }
    const std::size_t chunk_length = u32(data + offset);
    const std::uint32_t type = u32(data + offset + 4);
    if (chunk_length > out.length - offset - 8) {
      throw InputError(where(name, 0, "GLB chunk " + std::to_string(index) + " length " +
                                          std::to_string(chunk_length) + " runs past the GLB end"));
    }
    if (index == 0 && type != kJson) throw InputError(where(name, 0, "GLB first chunk is not JSON"));
    if (index == 0) {
      if (chunk_length == 0) throw InputError(where(name, 0, "GLB JSON chunk is empty"));
      out.json_offset = offset + 8;
      out.json_size = chunk_length;
    } else if (type == kJson) {
      throw InputError(where(name, 0, "GLB has a second JSON chunk"));
    } else if (type == kBin) {
      if (index != 1) throw InputError(where(name, 0, "GLB BIN chunk is not the second chunk"));
      out.bin_offset = offset + 8;
      out.bin_size = chunk_length;
    }
    // Chunks start 4-byte aligned (spec); a writer that forgot the padding leaves the next header misaligned.
    if (chunk_length % 4 != 0 && offset + 8 + chunk_length < out.length) {
      throw InputError(where(name, 0, "GLB chunk " + std::to_string(index) + " length " +
                                          std::to_string(chunk_length) + " not a multiple of 4"));
    }
    offset += 8 + chunk_length;
    ++index;
  }
  if (index == 0) throw InputError(where(name, 0, "GLB has no JSON chunk"));
  return out;
}

}  // namespace twinslam::twin::detail
