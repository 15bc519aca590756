#pragma once
// Nominal GPS and Galileo constellations as almanacs, and the satellites above a receiver's elevation mask.
//  - GPS: the 24 reference slots of the GPS SPS Performance Standard (Table 3-1: six planes, 55 deg), on circular
//    orbits of half a sidereal day;
//    the slots' right ascensions are turned into Earth-fixed node longitudes with that table's Greenwich hour angle,
//    so t = 0 is the table's epoch as far as the sky's geometry goes.
//  - Galileo: the Walker 24/3/1 pattern of its nominal constellation (three planes, 56 deg, 29 600 km).
// Time: seconds since that epoch (t_s); the scenario's `gnss.epoch_s` shifts it to vary the sky.
#include <vector>

#include <Eigen/Core>

#include "twinslam/gnss/orbit.hpp"

namespace twinslam::gnss {

std::vector<OrbitElements> gps_nominal_constellation();
std::vector<OrbitElements> galileo_nominal_constellation();
// Both of the above.
std::vector<OrbitElements> nominal_constellation();

struct SatelliteInView {
  int id = 0;
  SatSystem system = SatSystem::kGps;
  Eigen::Vector3d p_ecef = Eigen::Vector3d::Zero();  // position at t_s [m, ECEF]
  double elevation_deg = 0, azimuth_deg = 0;
};

// Satellites of `almanac` at or above `mask_deg` of elevation seen from receiver_ecef at t_s.
std::vector<SatelliteInView> satellites_in_view(const std::vector<OrbitElements>& almanac,
                                                const Eigen::Vector3d& receiver_ecef, double t_s, double mask_deg);

}  // namespace twinslam::gnss
