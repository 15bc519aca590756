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

// Like the procedural city's (tools/sim/world): a 28 m x 28 m tower in a 48 m block with 12 m streets around it.
inline SceneHints hints_for(const Scenario& s) {
  SceneHints h = city_hints(s.city.size_m, 19.8);
  h.clear_radius_m = 36;
  return h;
}

}  // namespace twinslam::sim::testing
