#pragma once
// Shared fixtures of the simulator sensor tests: scene hints like the procedural cities' and the built-ins' flights.
#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"

namespace twinslam::sim::testing {

// Hints for a city of side size_m whose tallest building (footprint half-diagonal radius_m) stands off-centre.
inline SceneHints city_hints(double size_m, double radius_m) {
  SceneHints h;
  h.tall_building_center_W = Eigen::Vector2d(0.1 * size_m, -0.05 * size_m);
  h.tall_building_radius_m = radius_m;
  h.tall_building_height_m = 60;
  h.extent_W = {-size_m / 2, -size_m / 2, size_m / 2, size_m / 2};
  return h;
}

// The street grid of a procedural city of side size_m (48 m blocks, 12 m streets, odd count centred on the origin),
// with no buildings, one park (the block north-east of the first intersection) and 10 m street trees.
inline void add_street_grid(double size_m, SceneHints* h) {
  const double pitch = 60;
  int n = static_cast<int>(size_m / pitch);
  if (n % 2 == 0) --n;
  for (int k = 0; k + 1 < n; ++k) h->streets.east_m.push_back((k - n / 2 + 0.5) * pitch);
  h->streets.north_m = h->streets.east_m;
  h->streets.width_m = 12;
  if (n >= 3) {
    const double e0 = h->streets.east_m[0];
    h->open_areas_W.emplace_back(e0 + 6, e0 + 6, e0 + pitch - 6, e0 + pitch - 6);
  }
  h->furniture_top_m = 10;
}

// Like the procedural city's (tools/sim/world): a 28 m x 28 m tower in a 48 m block with 12 m streets around it.
inline SceneHints hints_for(const Scenario& s) {
  SceneHints h = city_hints(s.city.size_m, 19.8);
  h.clear_radius_m = 36;
  add_street_grid(s.city.size_m, &h);
  return h;
}

}  // namespace twinslam::sim::testing
