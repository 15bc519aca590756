#pragma once
// Reader of the smartLoc urban GNSS dataset's text format (TU Chemnitz; layout in ../shared/data/gnss/*/readme.txt):
// whitespace-separated lines, the first word naming the kind.
//   pseudorange3 t[s] range[m] variance[m^2] sat_x sat_y sat_z[m, ECEF] sat_id system elevation[deg] C/N0[dB-Hz]
//   point3       t[s] x y z[m, ECEF] + 9 covariance entries (zeros)
//   odom3        t[s] ...                 (wheel odometry: not used by the receiver, skipped)
// Malformed lines, non-finite numbers, a non-positive variance, an unknown kind or a time that goes backwards throw
// InputError "FILE:LINE: what".
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/gnss/observation.hpp"

namespace twinslam::gnss {

// The pseudorange3 lines grouped into epochs (consecutive lines with the same time), in file order.
std::vector<Epoch> read_smartloc_pseudoranges(const std::string& path);

struct TruthPoint {
  double t_s = 0;
  Eigen::Vector3d p_ecef = Eigen::Vector3d::Zero();  // [m, ECEF]
};

// The point3 lines.
std::vector<TruthPoint> read_smartloc_ground_truth(const std::string& path);

}  // namespace twinslam::gnss
