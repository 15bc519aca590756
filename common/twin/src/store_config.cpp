// Small parts of the store's interface (store.hpp): configuration checks, tile keys and origins.
#include <algorithm>
#include <cmath>
#include <string>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::twin {

void StoreConfig::validate() const {
  // Tiles of 1 m to 10 km; smaller ones make millions of files, larger ones lose the float32 precision budget.
  if (!(tile_size_m >= 1.0 && tile_size_m <= 10000.0)) {
    throw UsageError("tile size must be within [1, 10000] m, got " + std::to_string(tile_size_m));
  }
  if (!(point_spacing_m >= 0.01 && point_spacing_m <= tile_size_m)) {
    throw UsageError("point spacing must be within [0.01 m, tile size], got " + std::to_string(point_spacing_m));
  }
  if (position_bits < 8 || position_bits > 30) {
    throw UsageError("position bits must be within [8, 30] (Draco), got " + std::to_string(position_bits));
  }
  if (normal_bits < 4 || normal_bits > 24) {
    throw UsageError("normal bits must be within [4, 24], got " + std::to_string(normal_bits));
  }
}

std::string TileKey::str() const { return std::to_string(ix) + "_" + std::to_string(iy); }

Eigen::Vector3d tile_origin_W(const TileKey& key, double tile_size_m) {
  return {key.ix * tile_size_m, key.iy * tile_size_m, 0.0};
}

const TileInfo* TwinIndex::find(const TileKey& key) const {
  const auto it =
      std::lower_bound(tiles.begin(), tiles.end(), key, [](const TileInfo& t, const TileKey& k) { return t.key < k; });
  return it != tiles.end() && it->key == key ? &*it : nullptr;
}

}  // namespace twinslam::twin
