// Feeding the twin index from the tiled store (twin::load_tile) or from a MapTile's Draco bytes, and the paper's
// 150 m x 150 m window of tiles around a position. No PCL here: this file compiles in a second.
#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration {
namespace {

void add_points(TwinTileIndex& index, const twin::TileKey& key, const twin::Mesh& points_W, const std::string& what) {
  if (!points_W.p_W.empty() && points_W.n_W.size() != points_W.p_W.size()) {
    throw InputError(what + ": the point sampling has no normals");
  }
  index.add_tile(key, points_W.p_W, points_W.n_W);
}

}  // namespace

void add_tile_from_store(TwinTileIndex& index, const std::string& twin_dir, const twin::TwinIndex& store,
                         const twin::TileKey& key) {
  const twin::Tile tile = twin::load_tile(twin_dir, store, key);
  add_points(index, key, tile.points_W, twin_dir + ": tile " + key.str());
}

void add_tile_from_draco(TwinTileIndex& index, const twin::TileKey& key, const std::vector<std::uint8_t>& mesh_draco,
                         const std::vector<std::uint8_t>& points_draco) {
  const std::string what = "MapTile " + key.str() + " points_draco";
  if (points_draco.empty()) {
    if (!mesh_draco.empty()) throw InputError(what + ": empty, but the tile has triangles");
    index.add_tile(key, {}, {});
    return;
  }
  add_points(index, key, twin::decode_draco(points_draco.data(), points_draco.size(), what), what);
}

void add_tile_from_draco(TwinTileIndex& index, const twin::TileKey& key, const std::vector<std::uint8_t>& points_draco) {
  add_tile_from_draco(index, key, {}, points_draco);
}

std::vector<twin::TileKey> tiles_in_window(const twin::TwinIndex& store, const Eigen::Vector3d& p_W, double window_m) {
  if (!p_W.allFinite() || !(window_m > 0.0)) throw InputError("tile window: non-finite position or window <= 0 m");
  if (p_W.head<2>().cwiseAbs().maxCoeff() > kMaxWorldCoordinate_m || window_m > kMaxWorldCoordinate_m) {
    throw InputError("tile window: position or window beyond the world's extent (1e7 m)");
  }
  const double half = 0.5 * window_m, s = store.tile_size_m;
  const int ix0 = static_cast<int>(std::floor((p_W.x() - half) / s));
  const int ix1 = static_cast<int>(std::floor((p_W.x() + half) / s));
  const int iy0 = static_cast<int>(std::floor((p_W.y() - half) / s));
  const int iy1 = static_cast<int>(std::floor((p_W.y() + half) / s));
  std::vector<twin::TileKey> keys;
  for (const twin::TileInfo& t : store.tiles) {
    if (t.key.ix >= ix0 && t.key.ix <= ix1 && t.key.iy >= iy0 && t.key.iy <= iy1) keys.push_back(t.key);
  }
  return keys;  // store.tiles is sorted by key
}

}  // namespace twinslam::registration
