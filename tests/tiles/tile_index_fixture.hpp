#pragma once
// A synthetic twin index for the streamer's unit tests: a square grid of 50 m tiles, optionally with holes (cells
// without any geometry, which a store does not list).
#include <set>
#include <utility>

#include "twinslam/twin/store.hpp"

namespace twinslam::tiles::test {

// Tiles ix, iy in [lo, hi], minus `holes`.
inline twin::TwinIndex grid_index(int lo, int hi, const std::set<std::pair<int, int>>& holes = {},
                                  double tile_size_m = 50.0) {
  twin::TwinIndex index;
  index.twin_id = "testtwin";
  index.tile_size_m = tile_size_m;
  for (int ix = lo; ix <= hi; ++ix) {
    for (int iy = lo; iy <= hi; ++iy) {
      if (holes.count({ix, iy}) != 0) continue;
      twin::TileInfo info;
      info.key = {ix, iy};
      info.bounds_W = Eigen::AlignedBox3d(Eigen::Vector3d(ix * tile_size_m, iy * tile_size_m, 0),
                                          Eigen::Vector3d((ix + 1) * tile_size_m, (iy + 1) * tile_size_m, 30));
      index.tiles.push_back(info);
    }
  }
  return index;
}

}  // namespace twinslam::tiles::test
