#pragma once
// The route of a `streets` flight on the street grid of SceneHints (see flight_trajectory.hpp for what it contains).
// Private to the library.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim::detail {

inline constexpr double kStreetFillet_m = 6.0;       // corner radius at intersections: half a street [m]
inline constexpr double kFurnitureClearance_m = 4.0; // lowest flight above the street trees' tops [m]

// Corner points [m, W] for PlanarPath::filleted_polyline whose filleted length is at least length_m, deterministic
// from `seed`. Throws InputError "WHAT: KEY: ..." when the world has no street grid, the grid is too small for the
// route, or trajectory.altitude_m would fly into the street trees.
std::vector<Eigen::Vector3d> plan_street_route(const SceneHints& hints, const TrajectoryConfig& config,
                                               double length_m, std::uint64_t seed, const std::string& what);

}  // namespace twinslam::sim::detail
