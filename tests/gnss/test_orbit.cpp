// Satellite positions: the Keplerian propagation against an independent numerical integration of the two-body problem
// in an inertial frame (then turned into ECEF by the Earth's rotation), the constellation's geometry, and the signal's
// travel time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "twinslam/gnss/constellation.hpp"
#include "twinslam/gnss/frames.hpp"
#include "twinslam/gnss/orbit.hpp"

namespace twinslam::gnss {
namespace {

using State = Eigen::Matrix<double, 6, 1>;  // position then velocity [m, m/s], inertial

State two_body(const State& s, double gm) {
  State d;
  d.head<3>() = s.tail<3>();
  d.tail<3>() = -gm * s.head<3>() / std::pow(s.head<3>().norm(), 3);
  return d;
}

// Classical RK4 with a 1 s step: an integration that knows nothing of Kepler's equation.
State integrate(State s, double gm, double duration_s) {
  const double h = 1.0;
  for (double t = 0; t < duration_s - 1e-9; t += h) {
    const State k1 = two_body(s, gm), k2 = two_body(s + h / 2 * k1, gm), k3 = two_body(s + h / 2 * k2, gm),
                k4 = two_body(s + h * k3, gm);
    s += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return s;
}

// ECEF at t -> inertial frame aligned with ECEF at t = 0.
Eigen::Vector3d to_inertial(const Eigen::Vector3d& p_ecef, double t_s) {
  return Eigen::AngleAxisd(kEarthRotationRate * t_s, Eigen::Vector3d::UnitZ()) * p_ecef;
}

TEST(GnssOrbit, KeplerPropagationMatchesNumericalIntegrationOfTheTwoBodyProblem) {
  OrbitElements o;  // an eccentric, inclined orbit with all angles non-trivial
  o.sqrt_a = std::sqrt(26560e3);
  o.eccentricity = 0.02;
  o.inclination_rad = 0.96;
  o.raan_rad = 1.1;
  o.raan_rate_rad_s = 0;  // the integration has no J2
  o.arg_perigee_rad = 0.7;
  o.mean_anomaly_rad = 2.3;
  o.reference_time_s = 0;
  // Initial inertial state from positions 1 s apart on either side (central difference of the ECEF positions turned
  // into the inertial frame): velocity error ~ a * n^3 * h^2 / 6, negligible.
  const Eigen::Vector3d p0 = to_inertial(satellite_ecef(o, 0), 0);
  const Eigen::Vector3d v0 = (to_inertial(satellite_ecef(o, 0.5), 0.5) - to_inertial(satellite_ecef(o, -0.5), -0.5));
  State s;
  s << p0, v0;
  const double duration = 3 * 3600;
  const State end = integrate(s, gravitational_parameter(o.system), duration);
  const Eigen::Vector3d expected_ecef = Eigen::AngleAxisd(-kEarthRotationRate * duration, Eigen::Vector3d::UnitZ()) *
                                        Eigen::Vector3d(end.head<3>());
  EXPECT_LT((satellite_ecef(o, duration) - expected_ecef).norm(), 1.0);  // metres after three hours
  EXPECT_NEAR(satellite_ecef(o, duration).norm(), end.head<3>().norm(), 0.5);
}

TEST(GnssOrbit, GpsSatellitesRepeatTheirGroundTrackAfterASiderealDay) {
  // Two orbits of a GPS satellite take half a sidereal day each: the ECEF position repeats after one sidereal day
  // (86164.09 s), while half a day later it is on the other side of the Earth.
  for (const OrbitElements& o : gps_nominal_constellation()) {
    EXPECT_LT((satellite_ecef(o, 86164.09) - satellite_ecef(o, 0)).norm(), 100.0) << "GPS " << o.id;
    EXPECT_GT((satellite_ecef(o, 43200) - satellite_ecef(o, 0)).norm(), 20000e3) << "GPS " << o.id;
    EXPECT_NEAR(satellite_ecef(o, 1234).norm(), 26561.7e3, 1e3);
  }
}

TEST(GnssOrbit, ConstellationsHaveTheirNominalPlanesAndSkyCoverage) {
  EXPECT_EQ(gps_nominal_constellation().size(), 24u);
  EXPECT_EQ(galileo_nominal_constellation().size(), 24u);
  // Anywhere and any time the nominal GPS constellation shows >= 4 satellites above 10 deg (its design criterion);
  // with Galileo, a receiver in the open sees typically 14-22.
  const Eigen::Vector3d berlin = geodetic_to_ecef({52.5, 13.37, 80});
  const Eigen::Vector3d quito = geodetic_to_ecef({-0.2, -78.5, 2800});
  for (double t = 0; t < 86400; t += 1800) {
    for (const Eigen::Vector3d& p : {berlin, quito}) {
      EXPECT_GE(satellites_in_view(gps_nominal_constellation(), p, t, 10).size(), 4u) << t;
      const auto all = satellites_in_view(nominal_constellation(), p, t, 10);
      EXPECT_GE(all.size(), 10u) << t;
      for (const auto& s : all) EXPECT_GE(s.elevation_deg, 10);
    }
  }
}

TEST(GnssOrbit, SignalTravelTimeClosesTheLightTimeEquation) {
  const OrbitElements o = gps_nominal_constellation()[3];
  const Eigen::Vector3d rx = geodetic_to_ecef({52.5, 13.37, 80});
  const SignalGeometry g = signal_geometry(o, rx, 5000);
  EXPECT_NEAR(g.range_m, kSpeedOfLight * g.travel_s, 1e-6);
  EXPECT_LT((g.sat_ecef - satellite_ecef(o, 5000 - g.travel_s)).norm(), 1e-6);
  // The Earth turns by omega_e * travel during the flight: the range differs from the naive one by metres.
  const double naive = (satellite_ecef(o, 5000 - g.travel_s) - rx).norm();
  EXPECT_GT(std::abs(naive - g.range_m), 0.1);
  EXPECT_LT(std::abs(naive - g.range_m), 40.0);
}

}  // namespace
}  // namespace twinslam::gnss
