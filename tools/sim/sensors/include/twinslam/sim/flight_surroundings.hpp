#pragma once
// Which buildings and empty lots a flight passes: the twin's changes (missing, shifted and added buildings) are drawn
// among them first, so that the flight actually meets the places where the twin is wrong.
#include <vector>

#include "twinslam/sim/flight_trajectory.hpp"

namespace twinslam::sim {

inline constexpr double kSeenWithin_m = 15.0;  // a building this close to the path lines the street flown [m]

// Ids (increasing) of the buildings whose footprint comes within within_m [m] horizontally of the flight, sampled
// every 0.5 s.
std::vector<int> buildings_along_flight(const FlightTrajectory& trajectory, const std::vector<BuildingHint>& buildings,
                                        double within_m);

// Indices into lots_W (rectangles [min e, min n, max e, max n] [m, W]) of the lots within within_m of the flight.
std::vector<int> lots_along_flight(const FlightTrajectory& trajectory, const std::vector<Eigen::Vector4d>& lots_W,
                                   double within_m);

}  // namespace twinslam::sim
