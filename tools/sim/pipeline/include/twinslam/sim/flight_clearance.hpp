#pragma once
// Is the planned flight clear of the world? A drone that flies through a facade gives the estimator images no real
// flight has, so the simulator refuses it: the trajectory, sampled every sample_dt_s, must keep min_distance_m from
// every surface of the world except flat ground (what trajectory.altitude_m governs). Samples at most
// speed_mps * sample_dt_s apart and a margin of metres catch a flight through a wall too (its distance drops to 0
// there). Applies to procedural and real cities alike.
#include <string>

#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/world/city.hpp"

namespace twinslam::sim {

struct FlightClearanceConfig {
  double min_distance_m = 3.0;   // closest approach to a building, structure, tree or raised terrain [m]
  double sample_dt_s = 0.1;      // [s]
  double ground_band_m = 1.0;    // ground triangles lower than this above SceneHints::ground_z_m are not obstacles [m]
};

struct FlightClearance {
  double min_distance_m = 0;     // closest approach found (capped at the search radius, 50 m) [m]
  double t_s = 0;                // when [s]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // where [m, W]
  int building = kNoBuilding;    // what it came closest to (kNoBuilding: a structure, tree or terrain)
};

// The closest approach of the flight to the world's obstacles.
FlightClearance measure_flight_clearance(const City& city, const FlightTrajectory& trajectory,
                                         const FlightClearanceConfig& config = {});

// Throws InputError "SCENARIO: KEY: the flight passes 1.2 m from building 12 ('name') at t = 35.0 s (...)" when the
// flight comes closer than config.min_distance_m; KEY is what to change: trajectory.waypoints for waypoints,
// trajectory.altitude_m for loops, survey and streets.
void require_flight_clearance(const Scenario& scenario, const City& city, const FlightTrajectory& trajectory,
                              const FlightClearanceConfig& config = {});

}  // namespace twinslam::sim
