#pragma once
// Nearest-twin-point lookup for ICP (paper eq. 2: b_j and its normal n_j), built incrementally from the twin's tiles.
// Each tile gets its own KD-tree (FLANN's, src/kdtree.hpp, hidden in twin_index.cpp) when it arrives and loses it
// when it leaves: registration indexes a 150 m window (and a prefetch ring) around the vehicle, so a keyframe's query touches a constant
// number of trees and nothing is rebuilt per registration (the paper code rebuilt a KD-tree over a +-350 m crop per
// call; bench_registration measures both). Why per-tile trees and not a voxel hash: services/registration/README.md.
// Tiles are squares of `tile_size_m` on the store's grid (tile (ix, iy) covers e in [ix s, (ix+1) s), n likewise); a
// query looks into every tile whose points' bounding box is within max_dist of it, so queries near a tile border
// find points of the neighbour. Results do not depend on the order tiles arrived in (ties: the lower tile key).
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/twin/store.hpp"

namespace twinslam::registration {

struct TwinMatch {
  Eigen::Vector3d p_W;      // nearest twin point [m, W]
  Eigen::Vector3d n_W;      // its unit normal [W]
  double distance_m = 0.0;  // |p_W - query| [m]
};

// W is a local ENU frame: no twin, vehicle or landmark lies farther than this from its origin. Coordinates beyond it
// (a corrupt or hostile sample) are refused before they become tile numbers (ints) or voxel keys.
inline constexpr double kMaxWorldCoordinate_m = 1e7;

class TwinTileIndex {
 public:
  explicit TwinTileIndex(double tile_size_m = 50.0);  // the store's tile side [m]; InputError if not > 0
  ~TwinTileIndex();
  TwinTileIndex(TwinTileIndex&&) noexcept;
  TwinTileIndex& operator=(TwinTileIndex&&) noexcept;

  // Builds the tile's tree (replacing a tile of the same key). Points may lie anywhere (bounding box is computed);
  // InputError for size mismatch, non-finite values or a normal that is not unit length (+-1e-3).
  void add_tile(const twin::TileKey& key, const std::vector<Eigen::Vector3d>& points_W,
                const std::vector<Eigen::Vector3d>& normals_W);
  bool remove_tile(const twin::TileKey& key);  // false if the tile was not there
  bool contains(const twin::TileKey& key) const;
  std::vector<twin::TileKey> keys() const;  // sorted
  std::size_t tile_count() const;
  std::size_t point_count() const;
  double tile_size_m() const { return tile_size_m_; }
  std::size_t memory_bytes() const;  // points, normals and trees held (estimate)

  // Nearest twin point within max_dist_m of p_W (over all tiles), or nothing.
  std::optional<TwinMatch> nearest(const Eigen::Vector3d& p_W, double max_dist_m) const;
  std::vector<std::optional<TwinMatch>> nearest_batch(const std::vector<Eigen::Vector3d>& p_W, double max_dist_m) const;

  struct Tile;  // defined in twin_index.cpp (PCL stays out of this header)

 private:
  struct Best;  // the nearest point so far and its tile's key
  static void search_tile(const twin::TileKey& key, const Tile& t, const Eigen::Vector3d& p_W, double max_sq,
                          Best& best);
  double tile_size_m_;
  double spill_m_ = 0.0;  // farthest any tile's points reach outside its square [m]
  std::map<twin::TileKey, std::unique_ptr<Tile>> tiles_;
};

// Loads a stored tile's point sampling with normals (twin::load_tile) into the index; InputError as load_tile.
void add_tile_from_store(TwinTileIndex& index, const std::string& twin_dir, const twin::TwinIndex& store,
                         const twin::TileKey& key);
// The two Draco buffers of a MapTile message (what the DDS node receives). ICP needs points with normals, so only
// `points_draco` is indexed; `mesh_draco` is not decoded (the store samples points on every triangle, so a tile with
// triangles always has points). Empty `points_draco`: an empty tile if the mesh is empty too, else InputError (the
// tile would look like free space to ICP). InputError names the tile on bad bytes or points without normals.
void add_tile_from_draco(TwinTileIndex& index, const twin::TileKey& key, const std::vector<std::uint8_t>& mesh_draco,
                         const std::vector<std::uint8_t>& points_draco);
// Only the point buffer (empty: an empty tile), for callers that hold no mesh (WindowedTwin keeps only the points).
void add_tile_from_draco(TwinTileIndex& index, const twin::TileKey& key, const std::vector<std::uint8_t>& points_draco);

// Keys of the stored tiles that overlap the square window of side window_m centred on (e, n) of p_W (the paper's
// 150 m x 150 m local map), sorted.
std::vector<twin::TileKey> tiles_in_window(const twin::TwinIndex& store, const Eigen::Vector3d& p_W, double window_m);

}  // namespace twinslam::registration
