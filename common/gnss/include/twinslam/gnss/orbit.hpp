#pragma once
// Satellite positions from almanac-style Keplerian elements (IS-GPS-200, Table 20-IV, without the harmonic
// corrections that only broadcast ephemerides carry): an unperturbed ellipse whose ascending node regresses at
// Omega_dot, expressed in the Earth-fixed frame (ECEF) at the epoch, i.e. with the Earth's rotation since the
// reference time. Accurate to the almanac's own level (kilometres over days) — what a simulator needs; the
// pseudoranges it generates are then consistent with these very positions.
#include <Eigen/Core>

#include "twinslam/gnss/constants.hpp"

namespace twinslam::gnss {

struct OrbitElements {
  int id = 0;                        // PRN / satellite number within its system
  SatSystem system = SatSystem::kGps;
  double sqrt_a = 5153.7;            // square root of the semi-major axis [sqrt(m)]
  double eccentricity = 0;           // [-]
  double inclination_rad = 0.9599;   // i0 [rad] (55 deg)
  double raan_rad = 0;               // Omega_0: longitude of the ascending node at the start of the week [rad]
  double raan_rate_rad_s = -8.0e-9;  // Omega_dot [rad/s]
  double arg_perigee_rad = 0;        // omega [rad]
  double mean_anomaly_rad = 0;       // M0 at the reference time [rad]
  double reference_time_s = 0;       // toa: seconds of the week the elements refer to [s]
};

// G*M of the system's interface document.
double gravitational_parameter(SatSystem system);

// Satellite position [m, ECEF] at `t_s` seconds of the week (the same time scale as reference_time_s).
Eigen::Vector3d satellite_ecef(const OrbitElements& orbit, double t_s);

// The position `sat_ecef` given at transmission time, expressed in the ECEF frame of the reception time, `travel_s`
// later (the Earth turned by omega_e * travel_s meanwhile: the Sagnac correction).
Eigen::Vector3d rotate_to_reception(const Eigen::Vector3d& sat_ecef, double travel_s);

// What a receiver at `receiver_ecef` sees of a satellite at reception time t_rx_s: the signal left at
// t_rx_s - travel_s, from sat_ecef (in the ECEF frame of that transmission time, as broadcast ephemerides give it);
// range_m = | R3(omega_e travel_s) sat_ecef - receiver_ecef | = c travel_s, solved by fixed-point iteration.
struct SignalGeometry {
  Eigen::Vector3d sat_ecef = Eigen::Vector3d::Zero();  // at transmission [m, ECEF of transmission time]
  double travel_s = 0;                                 // [s]
  double range_m = 0;                                  // geometric range in the frame of reception [m]
};
SignalGeometry signal_geometry(const OrbitElements& orbit, const Eigen::Vector3d& receiver_ecef, double t_rx_s);

}  // namespace twinslam::gnss
