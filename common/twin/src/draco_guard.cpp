// Reads the element counts at the head of a Draco bitstream (draco_guard.hpp). The layouts follow Draco 1.5's
// decoders: PointCloudDecoder::Decode (header, metadata from 1.3), the KD-tree point cloud's int32 point count,
// MeshSequentialDecoder (faces, points) and MeshEdgebreakerDecoderImpl (new vertices before 2.2, vertices, faces,
// attribute data, symbols, split symbols); fixed-width integers before 2.0 (sequential: before 2.2), varints after.
#include "draco_guard.hpp"

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>

#include <algorithm>

namespace twinslam::twin::detail {
namespace {

// Bounds no real geometry reaches, tight enough that what Draco then allocates per attribute (elements times up to
// 255 components of 8 bytes) stays below a gigabyte for the inputs a fuzzer makes. Real meshes spend more than a
// byte per triangle (edgebreaker connectivity is about 2 bits, the quantized positions 10-20 bits a vertex); a
// point cloud's KD-tree more than a bit per point. The absolute cap keeps one tile's tables bounded however large
// the file (a twin tile holds tens of thousands of triangles, a 3D Tiles tile rarely a million).
constexpr double kMaxFacesPerByte = 32.0;
constexpr double kMaxPointsPerByte = 8.0;
constexpr std::uint64_t kMaxElements = 1ULL << 24;

std::uint64_t element_limit(std::size_t size, double per_byte) {
  const double by_size = per_byte * static_cast<double>(size) + 64.0;
  return std::min<std::uint64_t>(kMaxElements, static_cast<std::uint64_t>(by_size));
}

// One count: a uint32 in older bitstreams, a varint in newer ones. False when the bytes end first.
bool read_count(draco::DecoderBuffer& buffer, bool fixed_width, std::uint64_t& out) {
  if (fixed_width) {
    std::uint32_t v = 0;
    if (!buffer.Decode(&v)) return false;
    out = v;
    return true;
  }
  out = 0;
  for (int shift = 0; shift < 35; shift += 7) {  // Draco's varint for uint32: at most 5 bytes
    std::uint8_t byte = 0;
    if (!buffer.Decode(&byte)) return false;
    out |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
    if ((byte & 0x80) == 0) return true;
  }
  return false;
}

std::string too_many(const char* what, std::uint64_t n, std::size_t size) {
  return "claims " + std::to_string(n) + " " + what + " in " + std::to_string(size) + " bytes";
}

std::string point_cloud_problem(draco::DecoderBuffer& buffer, std::size_t size) {
  std::int32_t num_points = 0;
  if (!buffer.Decode(&num_points)) return "";
  if (num_points < 0 || static_cast<std::uint64_t>(num_points) > element_limit(size, kMaxPointsPerByte)) {
    return too_many("points", static_cast<std::uint32_t>(num_points), size);
  }
  return "";
}

std::string sequential_mesh_problem(draco::DecoderBuffer& buffer, std::uint16_t version, std::size_t size) {
  const bool fixed = version < DRACO_BITSTREAM_VERSION(2, 2);
  std::uint64_t faces = 0, points = 0;
  if (!read_count(buffer, fixed, faces) || !read_count(buffer, fixed, points)) return "";
  if (faces > element_limit(size, kMaxFacesPerByte)) return too_many("faces", faces, size);
  if (points > element_limit(size, 3.0 * kMaxFacesPerByte)) return too_many("points", points, size);
  return "";
}

std::string edgebreaker_mesh_problem(draco::DecoderBuffer& buffer, std::uint16_t version, std::size_t size) {
  std::uint8_t traversal = 0;
  if (!buffer.Decode(&traversal)) return "";
  const bool fixed = version < DRACO_BITSTREAM_VERSION(2, 0);
  std::uint64_t new_vertices = 0, vertices = 0, faces = 0, symbols = 0, split_symbols = 0;
  if (version < DRACO_BITSTREAM_VERSION(2, 2) && !read_count(buffer, fixed, new_vertices)) return "";
  if (!read_count(buffer, fixed, vertices) || !read_count(buffer, fixed, faces)) return "";
  if (faces > element_limit(size, kMaxFacesPerByte)) return too_many("faces", faces, size);
  std::uint8_t attribute_data = 0;
  if (!buffer.Decode(&attribute_data) || !read_count(buffer, fixed, symbols) ||
      !read_count(buffer, fixed, split_symbols)) {
    return "";
  }
  // The corner table is sized for the encoded vertices plus one per split symbol, and for the new vertices.
  const std::uint64_t table_vertices = vertices + std::max(split_symbols, new_vertices);
  if (table_vertices > element_limit(size, 3.0 * kMaxFacesPerByte)) return too_many("vertices", table_vertices, size);
  return "";
}

}  // namespace

std::string draco_count_problem(const std::uint8_t* data, std::size_t size) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::DracoHeader header;
  if (!draco::PointCloudDecoder::DecodeHeader(&buffer, &header).ok()) return "";
  const std::uint16_t version = DRACO_BITSTREAM_VERSION(header.version_major, header.version_minor);
  buffer.set_bitstream_version(version);
  if (version >= DRACO_BITSTREAM_VERSION(1, 3) && (header.flags & METADATA_FLAG_MASK)) {
    draco::MetadataDecoder metadata_decoder;
    draco::GeometryMetadata metadata;
    if (!metadata_decoder.DecodeGeometryMetadata(&buffer, &metadata)) return "";
  }
  if (header.encoder_type == draco::POINT_CLOUD && header.encoder_method == draco::POINT_CLOUD_KD_TREE_ENCODING &&
      version < DRACO_BITSTREAM_VERSION(2, 3)) {
    // These older KD-tree streams carry a second point count inside the attribute data, after headers of variable
    // length, and Draco sizes the attribute values from it unchecked (fuzzing: 3.4 GB from 413 bytes). No current
    // encoder writes them (Draco 1.3, 2018, moved to 2.3), so they are refused rather than parsed that deep.
    return "KD-tree point cloud bitstream " + std::to_string(header.version_major) + "." +
           std::to_string(header.version_minor) + " (before 2.3) is not supported";
  }
  if (header.encoder_type == draco::POINT_CLOUD) return point_cloud_problem(buffer, size);
  if (header.encoder_type != draco::TRIANGULAR_MESH) return "";
  if (header.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) return sequential_mesh_problem(buffer, version, size);
  if (header.encoder_method == draco::MESH_EDGEBREAKER_ENCODING) return edgebreaker_mesh_problem(buffer, version, size);
  return "";
}

}  // namespace twinslam::twin::detail
