#pragma once
// One epoch of pseudoranges, as a receiver (or the smartLoc dataset, or the simulator's pseudoranges.csv) gives them.
#include <vector>

#include <Eigen/Core>

#include "twinslam/gnss/constants.hpp"

namespace twinslam::gnss {

struct Pseudorange {
  int satellite_id = 0;
  SatSystem system = SatSystem::kGps;
  double range_m = 0;                                  // measured pseudorange [m] (satellite clock etc. removed)
  double sigma_m = 5;                                  // its stated standard deviation [m]
  Eigen::Vector3d satellite_ecef = Eigen::Vector3d::Zero();  // at transmission time, in the ECEF frame of that time
  double elevation_deg = 0;                            // as the receiver reports it [deg]
  double cn0_dbhz = 0;                                 // carrier-to-noise density [dB-Hz]
};

struct Epoch {
  double t_s = 0;                                      // receiver time of the epoch [s]
  std::vector<Pseudorange> observations;
};

}  // namespace twinslam::gnss
