#include "gnss_signal_model.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace twinslam::sim::gnss_model {

using namespace twinslam::gnss;

LocalFrame::LocalFrame(const Origin& o)
    : origin_ecef(geodetic_to_ecef({o.lat_deg, o.lon_deg, o.alt_m})),
      R_W_ECEF(rotation_enu_from_ecef(o.lat_deg, o.lon_deg)) {}

namespace {

// Stated sigma of a pseudorange as a receiver reports it: worse at low elevation [m].
double stated_sigma_m(double elevation_deg) {
  return std::min(10.0, 1.5 / std::sin(std::max(elevation_deg, 5.0) * std::numbers::pi / 180));
}

// Thin-shell ionospheric obliquity factor (shell at 350 km): slant / vertical delay at this elevation.
double ionosphere_obliquity(double elevation_deg) {
  const double ratio = 6371.0 / (6371.0 + 350.0) * std::cos(elevation_deg * std::numbers::pi / 180);
  return 1 / std::sqrt(1 - ratio * ratio);
}

}  // namespace

void start_clock(const RaytraceGnssModel& m, ErrorState& e) {
  e.clock_m = std::uniform_real_distribution<double>(-m.clock_bias_max_m, m.clock_bias_max_m)(e.rng);
  e.drift_mps = m.clock_drift_sigma_mps * e.normal(e.rng);
}

void advance_epoch(bool first, double dt_s, const RaytraceGnssModel& m, ErrorState& e) {
  e.clock_m += e.drift_mps * dt_s;
  e.ionosphere_m = gauss_markov(e.ionosphere_m, first, dt_s, m.ionosphere_sigma_m, m.atmosphere_tau_s, e);
}

double gauss_markov(double x, bool first, double dt_s, double sigma, double tau_s, ErrorState& e) {
  if (first) return sigma * e.normal(e.rng);
  const double phi = std::exp(-dt_s / tau_s);
  return phi * x + std::sqrt(1 - phi * phi) * sigma * e.normal(e.rng);
}

SatelliteLook look_at(const OrbitElements& orbit, const Eigen::Vector3d& rx_ecef, double t_rx) {
  SatelliteLook s;
  s.geometry = signal_geometry(orbit, rx_ecef, t_rx);
  s.sat_rx_ecef = rotate_to_reception(s.geometry.sat_ecef, s.geometry.travel_s);
  s.look = look_angles(rx_ecef, s.sat_rx_ecef);
  return s;
}

double nominal_cn0_dbhz(double elevation_deg) {
  const double sin_el = std::sin(elevation_deg * std::numbers::pi / 180);
  return 35 + 13 * sin_el;
}

double draw_direct_cn0_dbhz(double elevation_deg, ErrorState& e) {
  return nominal_cn0_dbhz(elevation_deg) + 1.5 * e.normal(e.rng);
}

double reflection_error(const SignalPath& path, const RaytraceGnssModel& m, ErrorState& e, double* cn0_dbhz) {
  if (!path.reflected) return 0;
  const double loss_db = std::uniform_real_distribution<double>(m.reflection_loss_min_db, m.reflection_loss_max_db)(e.rng);
  if (!path.line_of_sight) {
    *cn0_dbhz -= loss_db;
    return path.extra_path_m;
  }
  const double chip_m = kSpeedOfLight / 1.023e6;
  if (path.extra_path_m > chip_m + m.correlator_half_spacing_m) return 0;
  const double alpha = std::pow(10.0, -loss_db / 20);
  const double phi = std::uniform_real_distribution<double>(0, 2 * std::numbers::pi)(e.rng);
  *cn0_dbhz += 20 * std::log10(std::abs(std::complex<double>(1 + alpha * std::cos(phi), alpha * std::sin(phi))));
  return alpha * std::min(path.extra_path_m, m.correlator_half_spacing_m) * std::cos(phi) /
         (1 + alpha * std::cos(phi));
}

Pseudorange make_pseudorange(const OrbitElements& orbit, const SatelliteLook& s, double path_error_m,
                             double cn0_dbhz, double dt_s, const RaytraceGnssModel& m, ErrorState& e) {
  const double sin_el = std::sin(s.look.elevation_deg * std::numbers::pi / 180);
  // The satellite's own residual: first-order Gauss-Markov (stationary start), mapped by 1/sin(elevation).
  const auto key = std::make_pair(static_cast<int>(orbit.system), orbit.id);
  const bool first = e.satellite_m.find(key) == e.satellite_m.end();
  double& own = e.satellite_m[key];
  own = gauss_markov(first ? 0 : own, first, dt_s, m.per_satellite_sigma_m, m.atmosphere_tau_s, e);
  const double noise = m.noise_at_45dbhz_m * std::pow(10.0, (45 - cn0_dbhz) / 20) * e.normal(e.rng);
  const double system_offset = orbit.system == SatSystem::kGalileo ? m.galileo_offset_m : 0;
  Pseudorange out;
  out.satellite_id = orbit.id;
  out.system = orbit.system;
  const double atmosphere = e.ionosphere_m * ionosphere_obliquity(s.look.elevation_deg) + own / sin_el;
  out.range_m = s.geometry.range_m + path_error_m + e.clock_m + system_offset + atmosphere + noise;
  out.sigma_m = stated_sigma_m(s.look.elevation_deg);
  out.satellite_ecef = s.geometry.sat_ecef;
  out.elevation_deg = s.look.elevation_deg;
  out.cn0_dbhz = cn0_dbhz;
  return out;
}

GnssSample to_sample(const Fix& fix, std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const LocalFrame& frame) {
  GnssSample s;
  s.stamp_ns = stamp_ns;
  const Geodetic g = ecef_to_geodetic(fix.p_ecef);
  s.latitude_deg = g.latitude_deg;
  s.longitude_deg = g.longitude_deg;
  s.altitude_m = g.height_m;
  const Eigen::Matrix3d R = rotation_enu_from_ecef(g.latitude_deg, g.longitude_deg);
  const Eigen::Vector3d sd = (R * fix.cov_ecef * R.transpose()).diagonal().cwiseSqrt();
  s.std_east_m = sd.x();
  s.std_north_m = sd.y();
  s.std_up_m = sd.z();
  s.num_satellites = fix.satellites_used;
  s.true_p_W = p_W;
  s.bias_W = frame.to_W(fix.p_ecef) - p_W;
  return s;
}

PseudorangeRow to_row(std::int64_t stamp_ns, const Pseudorange& p, bool line_of_sight) {
  return PseudorangeRow{stamp_ns,        p.satellite_id, static_cast<int>(p.system), p.range_m, p.satellite_ecef,
                        p.elevation_deg, p.cn0_dbhz,     line_of_sight};
}

}  // namespace twinslam::sim::gnss_model
