#pragma once
// The tiled twin store (`twinslam twin build`): the mesh in W cut into a grid of square tiles (all heights), each tile
// holding its triangles and an area-uniform point sampling with normals, both Draco-compressed, plus an index.
// Layout of TWIN_DIR:
//   index.json                    origin, twin_id, tile size, spacing, extent, totals, per tile key/bounds/counts/files
//   tiles/<ix>_<iy>.mesh.drc      Draco triangle mesh of the tile (vertices in W)
//   tiles/<ix>_<iy>.points.drc    Draco point cloud with a NORMAL attribute (points in W)
// Tile (ix, iy) covers e in [ix * size, (ix + 1) * size), n in [iy * size, (iy + 1) * size) in W.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/twin/geo.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

struct StoreConfig {
  double tile_size_m = 50.0;        // side of a square tile [m]
  double point_spacing_m = 0.5;     // mean spacing of the area-uniform point sampling [m] (paper's code: 0.2-0.7)
  int position_bits = 20;           // Draco quantization of positions: error <= tile extent / 2^bits (~0.1 mm at 50 m)
  int normal_bits = 10;             // Draco quantization of normals
  std::uint64_t seed = 1;           // point sampling is deterministic for a seed
  void validate() const;            // throws UsageError naming the bad value
};

struct TileKey {
  int ix = 0;
  int iy = 0;
  std::string str() const;          // "<ix>_<iy>"
  bool operator==(const TileKey&) const = default;
  auto operator<=>(const TileKey&) const = default;
};

struct TileInfo {
  TileKey key;
  Eigen::AlignedBox3d bounds_W;     // of the tile's content [m]
  std::size_t triangles = 0;
  std::size_t points = 0;
  std::size_t bytes = 0;            // both Draco files
};

struct TwinIndex {
  GeoOrigin origin;
  std::string twin_id;              // stable id of this twin (from its content), prefix of MapTile keys
  double tile_size_m = 50.0;
  double point_spacing_m = 0.5;
  Eigen::AlignedBox3d extent_W;
  std::size_t triangles = 0;
  std::size_t points = 0;
  std::vector<TileInfo> tiles;      // sorted by key
};

// One decoded tile.
struct Tile {
  TileInfo info;
  Mesh mesh_W;                      // triangles of the tile
  Mesh points_W;                    // p_W + n_W, no triangles
};

// Cuts, samples, encodes and writes the store; returns its index (also written as index.json). Throws InputError
// when out_dir cannot be written.
TwinIndex build_twin_store(const Mesh& mesh_W, const GeoOrigin& origin, const StoreConfig& config,
                           const std::string& out_dir);

// Throws InputError naming the file and problem for a missing or malformed index.
TwinIndex read_twin_index(const std::string& twin_dir);

// Raw Draco bytes of a tile as stored (what MapTile carries); throws InputError if missing.
std::vector<std::uint8_t> read_tile_file(const std::string& twin_dir, const TileKey& key, bool points);

// Draco encode / decode of a mesh (triangles) or a point set with normals. Decode throws InputError naming `what`.
std::vector<std::uint8_t> encode_mesh(const Mesh& mesh_W, const StoreConfig& config);
std::vector<std::uint8_t> encode_points(const Mesh& points_W, const StoreConfig& config);
Mesh decode_draco(const std::uint8_t* data, std::size_t size, const std::string& what);

}  // namespace twinslam::twin
