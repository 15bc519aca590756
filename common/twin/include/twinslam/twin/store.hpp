#pragma once
// The tiled twin store (`twinslam twin build`): the mesh in W cut into a grid of square tiles (all heights), each tile
// holding its triangles and an area-uniform point sampling with normals, both Draco-compressed, plus an index.
// Layout of TWIN_DIR:
//   index.json                    origin, twin_id, tile size, spacing, extent, totals, per tile key/bounds/counts/files
//   tiles/<ix>_<iy>.mesh.drc      Draco triangle mesh of the tile (only if it has triangles)
//   tiles/<ix>_<iy>.points.drc    Draco point cloud with a NORMAL attribute (only if it has points)
// Tile (ix, iy) covers e in [ix * size, (ix + 1) * size), n in [iy * size, (iy + 1) * size) in W.
// Draco positions are float32 and quantized over the tile's bounding box; float32 steps are 0.5 mm at 5 km from the
// origin and 2 mm at 30 km. So each file stores positions relative to its tile's origin corner (ix * size, iy * size,
// 0) and carries that offset as Draco geometry metadata ("twinslam_origin_W", 3 doubles); decode_draco adds it back, so
// decoded coordinates are in W whoever decodes the bytes. Position error after a round trip (per coordinate):
//   <= range / (2 * (2^position_bits - 1)) + |p - origin| * 2^-24,  range = largest side of the tile's bounding box;
// a 50 m x 50 m x 100 m tile at the default 20 bits: <= 0.05 mm + 0.01 mm.
#include <functional>
#include <cstddef>
#include <cstdint>
#include <optional>
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
  Eigen::Vector3d origin_W = Eigen::Vector3d::Zero();  // offset of the Draco positions (tile_origin_W) [m]
  std::size_t mesh_bytes = 0;       // 0: no mesh file (no triangles)
  std::size_t points_bytes = 0;     // 0: no points file (no points)
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
  int format_version = 1;           // index.json "format_version"

  const TileInfo* find(const TileKey& key) const;  // nullptr if the tile is not stored
};

// One decoded tile.
struct Tile {
  TileInfo info;
  Mesh mesh_W;                      // triangles of the tile
  Mesh points_W;                    // p_W + n_W, no triangles
};

// Cuts, samples, encodes and writes the store; returns its index (also written as index.json, last, through a rename).
// A mesh without triangles but with one normal per point is a point set: its points are the tiles' points. Rebuilding
// into the same folder removes its old tiles/*.drc first. Throws InputError when out_dir cannot be written or the
// mesh is empty or malformed.
// on_tile(done, total), if given, is called before the first tile and after each one (progress of long builds).
using TileProgress = std::function<void(std::size_t done, std::size_t total)>;
TwinIndex build_twin_store(const Mesh& mesh_W, const GeoOrigin& origin, const StoreConfig& config,
                           const std::string& out_dir, const TileProgress& on_tile = {});

// Throws InputError naming the file and problem for a missing or malformed index.
TwinIndex read_twin_index(const std::string& twin_dir);

// Raw Draco bytes of a tile as stored (what MapTile carries); throws InputError if missing.
std::vector<std::uint8_t> read_tile_file(const std::string& twin_dir, const TileKey& key, bool points);

// Reads and decodes both files of a stored tile (a missing kind, e.g. no triangles, stays empty). Throws InputError
// if `key` is not in the index, a file is missing or corrupt, or its counts differ from the index.
Tile load_tile(const std::string& twin_dir, const TwinIndex& index, const TileKey& key);

// South-west-bottom corner (ix * size, iy * size, 0) of a tile [m, W]: the offset of its Draco positions.
Eigen::Vector3d tile_origin_W(const TileKey& key, double tile_size_m);

// Draco encode / decode of a mesh (triangles) or a point set with normals. Decode throws InputError naming `what`.
// origin_W: offset subtracted before float32 conversion and stored in the file (see above); default: the mesh's
// bounding-box minimum rounded down to whole metres. Encoding throws InputError for an empty or non-finite input
// (encode_points also without one normal per point).
std::vector<std::uint8_t> encode_mesh(const Mesh& mesh_W, const StoreConfig& config,
                                      const std::optional<Eigen::Vector3d>& origin_W = std::nullopt);
std::vector<std::uint8_t> encode_points(const Mesh& points_W, const StoreConfig& config,
                                        const std::optional<Eigen::Vector3d>& origin_W = std::nullopt);
// A mesh file decodes to p_W + triangles, a point cloud to p_W (+ n_W if it has normals).
Mesh decode_draco(const std::uint8_t* data, std::size_t size, const std::string& what);

}  // namespace twinslam::twin
