#pragma once
// Stanford PLY (ascii, binary_little_endian, binary_big_endian) <-> Mesh. Reads vertex x y z (float or double) with
// optional nx ny nz, faces from a `vertex_indices` / `vertex_index` list (any integer count and index types, polygons
// fan-triangulated); every other property or element is skipped by its size. A file with normals and no faces is a
// point set (p + n). The simulator's twin PLY (doubles, face building_id and kind, `comment twinslam_origin LAT LON
// ALT`) is one case of this. Coordinates are returned as stored: the caller decides the frame (load.hpp).
#include <optional>
#include <string>

#include "twinslam/twin/geo.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

struct PlyFile {
  Mesh mesh;                         // as stored in the file
  std::optional<GeoOrigin> origin;   // from `comment twinslam_origin LAT LON ALT`, if present
};

// Throws InputError "<path>: <reason>" (bad header, truncated body, index out of range, non-finite coordinate...).
PlyFile read_ply(const std::string& path);

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// Writes vertices as doubles (with nx ny nz when the mesh has normals) and triangles as `list uchar int
// vertex_indices`; with `origin`, adds the twinslam_origin comment. Throws InputError if the file cannot be written.
void write_ply(const std::string& path, const Mesh& mesh, PlyFormat format,
               const std::optional<GeoOrigin>& origin = std::nullopt);

}  // namespace twinslam::twin
