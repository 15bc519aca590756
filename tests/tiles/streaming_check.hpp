#pragma once
// The acceptance rule of the tiles service, checked on a flown path: every tile that ever comes within 75 m of the
// vehicle (horizontal distance to the tile's square) has arrived, and arrived before the vehicle first came within
// 50 m of it; no tile arrived twice; and every tile that arrived was near the vehicle when it did (the window's
// corner: half side * sqrt(2)), so the service does not simply stream the whole city.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "twinslam/tiles/tile_grid.hpp"

namespace twinslam::tiles::test {

struct Receipt {
  int update = -1;  // index into the positions of the first arrival
  int count = 0;    // arrivals
};

// Returns how many tiles came within near_m (so a caller can check the path actually passed tiles).
inline int expect_streamed_in_time(const TileGrid& grid, const std::vector<Eigen::Vector3d>& positions,
                                   const std::map<twin::TileKey, Receipt>& received, double window_m = 150.0,
                                   double near_m = 75.0, double close_m = 50.0) {
  int near_tiles = 0;
  for (const TileRecord& info : grid.records()) {
    int first_near = -1, first_close = -1;
    for (int k = 0; k < static_cast<int>(positions.size()) && first_close < 0; ++k) {
      const double d = grid.distance_to_square(info.key, positions[k].head<2>());
      if (first_near < 0 && d < near_m) first_near = k;
      if (d < close_m) first_close = k;
    }
    const auto it = received.find(info.key);
    const std::string name = grid.wire_key(info.key);
    if (first_near >= 0) {
      ++near_tiles;
      EXPECT_NE(it, received.end()) << name << " came within " << near_m << " m at update " << first_near
                                    << " but never arrived";
    }
    if (it == received.end()) continue;
    EXPECT_EQ(it->second.count, 1) << name << " arrived " << it->second.count << " times";
    if (first_close > 0) {
      EXPECT_LT(it->second.update, first_close) << name << " arrived at update " << it->second.update
                                                << ", the vehicle was within " << close_m << " m at " << first_close;
    } else if (first_close == 0) {
      EXPECT_EQ(it->second.update, 0) << name << " was within " << close_m << " m at the start";
    }
    const double d = grid.distance_to_square(info.key, positions.at(it->second.update).head<2>());
    EXPECT_LE(d, 0.5 * window_m * std::sqrt(2.0) + 1e-6) << name << " arrived " << d << " m away from the vehicle";
  }
  return near_tiles;
}

}  // namespace twinslam::tiles::test
