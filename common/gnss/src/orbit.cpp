#include "twinslam/gnss/orbit.hpp"

#include <cmath>

namespace twinslam::gnss {

const char* system_name(SatSystem system) {
  switch (system) {
    case SatSystem::kGps: return "GPS";
    case SatSystem::kSbas: return "SBAS";
    case SatSystem::kGlonass: return "GLONASS";
    case SatSystem::kGalileo: return "Galileo";
    case SatSystem::kQzss: return "QZSS";
    case SatSystem::kBeidou: return "BeiDou";
  }
  return "system ?";
}

double gravitational_parameter(SatSystem system) {
  return system == SatSystem::kGalileo ? kGmGalileo : kGmGps;
}

namespace {

// Kepler's equation M = E - e sin E by Newton's method; e < 0.1 for navigation satellites, so a few steps suffice.
double eccentric_anomaly(double mean_anomaly, double e) {
  double E = mean_anomaly;
  for (int k = 0; k < 20; ++k) {
    const double step = (E - e * std::sin(E) - mean_anomaly) / (1 - e * std::cos(E));
    E -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return E;
}

}  // namespace

Eigen::Vector3d satellite_ecef(const OrbitElements& orbit, double t_s) {
  const double a = orbit.sqrt_a * orbit.sqrt_a;
  const double n = std::sqrt(gravitational_parameter(orbit.system) / (a * a * a));  // mean motion [rad/s]
  const double tk = t_s - orbit.reference_time_s;
  const double e = orbit.eccentricity;
  const double E = eccentric_anomaly(orbit.mean_anomaly_rad + n * tk, e);
  const double nu = std::atan2(std::sqrt(1 - e * e) * std::sin(E), std::cos(E) - e);  // true anomaly
  const double u = nu + orbit.arg_perigee_rad;                                        // argument of latitude
  const double r = a * (1 - e * std::cos(E));
  // The node's longitude in the Earth-fixed frame: its inertial drift minus the Earth's rotation since the start of
  // the week (IS-GPS-200 Table 20-IV, Omega_k).
  const double raan = orbit.raan_rad + (orbit.raan_rate_rad_s - kEarthRotationRate) * tk -
                      kEarthRotationRate * orbit.reference_time_s;
  const double x_orb = r * std::cos(u), y_orb = r * std::sin(u);
  const double ci = std::cos(orbit.inclination_rad), si = std::sin(orbit.inclination_rad);
  return {x_orb * std::cos(raan) - y_orb * ci * std::sin(raan), x_orb * std::sin(raan) + y_orb * ci * std::cos(raan),
          y_orb * si};
}

Eigen::Vector3d rotate_to_reception(const Eigen::Vector3d& sat_ecef, double travel_s) {
  const double angle = kEarthRotationRate * travel_s;
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * sat_ecef.x() + s * sat_ecef.y(), -s * sat_ecef.x() + c * sat_ecef.y(), sat_ecef.z()};
}

SignalGeometry signal_geometry(const OrbitElements& orbit, const Eigen::Vector3d& receiver_ecef, double t_rx_s) {
  SignalGeometry g;
  // Each step changes the travel time by (satellite speed / c) of the last change: ~1e-5, so three steps reach 1e-15 s.
  for (int k = 0; k < 5; ++k) {
    g.sat_ecef = satellite_ecef(orbit, t_rx_s - g.travel_s);
    g.range_m = (rotate_to_reception(g.sat_ecef, g.travel_s) - receiver_ecef).norm();
    g.travel_s = g.range_m / kSpeedOfLight;
  }
  g.range_m = (rotate_to_reception(g.sat_ecef, g.travel_s) - receiver_ecef).norm();
  return g;
}

}  // namespace twinslam::gnss
