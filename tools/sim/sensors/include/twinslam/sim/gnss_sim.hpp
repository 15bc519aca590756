#pragma once
// Simple GNSS model (the urban ray-traced one is a later issue): the antenna at the body origin, its ENU position plus
// white noise plus a slowly varying bias (first-order Gauss-Markov, tau = 60 s), converted to WGS84 latitude,
// longitude and ellipsoidal height with GeographicLib::LocalCartesian at the scenario origin.
// Per axis the stated std is sqrt(white^2 + bias^2): horizontal sigma_m, vertical 1.5 sigma_m; the bias takes 60 % of
// the std and the white noise 80 % (0.6^2 + 0.8^2 = 1).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/flight_trajectory.hpp"

namespace twinslam::sim {

struct GnssSample {
  std::int64_t stamp_ns = 0;
  double latitude_deg = 0, longitude_deg = 0, altitude_m = 0;  // WGS84, ellipsoidal height
  double std_east_m = 0, std_north_m = 0, std_up_m = 0;        // stated 1-sigma [m]
  int num_satellites = 0;
  Eigen::Vector3d true_p_W = Eigen::Vector3d::Zero();          // true antenna position [m, W]
  Eigen::Vector3d bias_W = Eigen::Vector3d::Zero();            // Gauss-Markov part of the error [m, W]
};

inline constexpr double kGnssBiasTau = 60.0;  // [s] correlation time of the bias

// At config.rate_hz over [0, trajectory.duration()].
std::vector<GnssSample> simulate_gnss(const FlightTrajectory& trajectory, const GnssSimConfig& config,
                                      const Origin& origin, std::uint64_t seed);

// The same for given stamps and true positions (p_W[i] at stamps_ns[i]); stamps strictly increasing.
std::vector<GnssSample> simulate_gnss_at(const std::vector<std::int64_t>& stamps_ns,
                                         const std::vector<Eigen::Vector3d>& p_W, const GnssSimConfig& config,
                                         const Origin& origin, std::uint64_t seed);

// WGS84 -> W (ENU at origin) [m]: what ingest/estimator do with a fix.
Eigen::Vector3d gnss_to_enu(const GnssSample& sample, const Origin& origin);

}  // namespace twinslam::sim
