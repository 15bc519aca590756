#include "twinslam/sim/gnss_raytrace.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <map>
#include <numbers>
#include <random>

#include "twinslam/core/error.hpp"
#include "twinslam/gnss/constellation.hpp"
#include "twinslam/gnss/frames.hpp"
#include "twinslam/gnss/receiver.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/world/signal_tracer.hpp"

namespace twinslam::sim {
namespace {

using namespace twinslam::gnss;

// The local frame W (ENU at the origin) in ECEF: p_ecef = origin_ecef + R_ECEF_W p_W (exactly what
// GeographicLib::LocalCartesian does).
struct LocalFrame {
  Eigen::Vector3d origin_ecef;
  Eigen::Matrix3d R_W_ECEF;
  explicit LocalFrame(const Origin& o)
      : origin_ecef(geodetic_to_ecef({o.lat_deg, o.lon_deg, o.alt_m})),
        R_W_ECEF(rotation_enu_from_ecef(o.lat_deg, o.lon_deg)) {}
  Eigen::Vector3d to_ecef(const Eigen::Vector3d& p_W) const { return origin_ecef + R_W_ECEF.transpose() * p_W; }
  Eigen::Vector3d to_W(const Eigen::Vector3d& p_ecef) const { return R_W_ECEF * (p_ecef - origin_ecef); }
};

// The random processes of the receiver and the sky: clock, the vertical ionosphere, one error state per satellite.
struct ErrorState {
  explicit ErrorState(std::seed_seq& seq) : rng(seq) {}
  std::mt19937_64 rng;
  std::normal_distribution<double> normal{0, 1};
  double clock_m = 0, drift_mps = 0;
  double ionosphere_m = 0;                             // vertical residual over the receiver [m]
  std::map<std::pair<int, int>, double> satellite_m;   // (system, id) -> its own zenith residual [m]
};

// Stated sigma of a pseudorange as a receiver reports it: worse at low elevation [m].
double stated_sigma_m(double elevation_deg) {
  return std::min(10.0, 1.5 / std::sin(std::max(elevation_deg, 5.0) * std::numbers::pi / 180));
}

// A first-order Gauss-Markov step of standard deviation sigma and correlation time tau (exact discretization); the
// first value is drawn from the stationary distribution.
double gauss_markov(double x, bool first, double dt_s, double sigma, double tau_s, ErrorState& e) {
  if (first) return sigma * e.normal(e.rng);
  const double phi = std::exp(-dt_s / tau_s);
  return phi * x + std::sqrt(1 - phi * phi) * sigma * e.normal(e.rng);
}

// Thin-shell ionospheric obliquity factor (shell at 350 km): slant / vertical delay at this elevation.
double ionosphere_obliquity(double elevation_deg) {
  const double ratio = 6371.0 / (6371.0 + 350.0) * std::cos(elevation_deg * std::numbers::pi / 180);
  return 1 / std::sqrt(1 - ratio * ratio);
}

// The range error a reflection causes, and its effect on C/N0 (cn0_dbhz is updated) [m]. NLOS: the receiver tracks
// the reflection, whole extra path, weaker. Direct + reflected: code multipath and fading (RaytraceGnssModel).
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

// One satellite's pseudorange at one epoch, or none if the signal cannot reach the receiver.
bool observe(const OrbitElements& orbit, const Eigen::Vector3d& rx_ecef, double t_rx, const LocalFrame& frame,
             const SignalTracer& tracer, const Eigen::Vector3d& p_W, double dt_s, const RaytraceGnssModel& m,
             ErrorState& e, Pseudorange* out, bool* los) {
  const SignalGeometry g = signal_geometry(orbit, rx_ecef, t_rx);
  const Eigen::Vector3d sat_rx = rotate_to_reception(g.sat_ecef, g.travel_s);
  const LookAngles look = look_angles(rx_ecef, sat_rx);
  if (look.elevation_deg < m.elevation_mask_deg) return false;
  const SignalPath path = tracer.trace(p_W, frame.R_W_ECEF * (sat_rx - rx_ecef).normalized(), true);
  if (!path.line_of_sight && !path.reflected) return false;
  const double sin_el = std::sin(look.elevation_deg * std::numbers::pi / 180);
  double cn0 = 35 + 13 * sin_el + 1.5 * e.normal(e.rng);
  const double path_error = reflection_error(path, m, e, &cn0);
  // The satellite's own residual: first-order Gauss-Markov (stationary start), mapped by 1/sin(elevation).
  const auto key = std::make_pair(static_cast<int>(orbit.system), orbit.id);
  const bool first = e.satellite_m.find(key) == e.satellite_m.end();
  double& own = e.satellite_m[key];
  own = gauss_markov(first ? 0 : own, first, dt_s, m.per_satellite_sigma_m, m.atmosphere_tau_s, e);
  const double noise = m.noise_at_45dbhz_m * std::pow(10.0, (45 - cn0) / 20) * e.normal(e.rng);
  const double system_offset = orbit.system == SatSystem::kGalileo ? m.galileo_offset_m : 0;
  out->satellite_id = orbit.id;
  out->system = orbit.system;
  const double atmosphere = e.ionosphere_m * ionosphere_obliquity(look.elevation_deg) + own / sin_el;
  out->range_m = g.range_m + path_error + e.clock_m + system_offset + atmosphere + noise;
  out->sigma_m = stated_sigma_m(look.elevation_deg);
  out->satellite_ecef = g.sat_ecef;
  out->elevation_deg = look.elevation_deg;
  out->cn0_dbhz = cn0;
  *los = path.line_of_sight;
  return true;
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

}  // namespace

RaytraceGnss simulate_gnss_raytrace(const std::vector<std::int64_t>& stamps_ns,
                                    const std::vector<Eigen::Vector3d>& p_W, const Origin& origin,
                                    const EmbreeScene& world, std::uint64_t seed, const RaytraceGnssModel& m) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32), 4u};
  ErrorState e(seq);
  e.clock_m = std::uniform_real_distribution<double>(-m.clock_bias_max_m, m.clock_bias_max_m)(e.rng);
  e.drift_mps = m.clock_drift_sigma_mps * e.normal(e.rng);
  const LocalFrame frame(origin);
  const SignalTracer tracer(world);
  const std::vector<OrbitElements> almanac = nominal_constellation();
  const ReceiverConfig receiver;
  RaytraceGnss out;
  Eigen::Vector3d guess = Eigen::Vector3d::Zero();  // the receiver starts from the Earth's centre, not the truth
  for (std::size_t i = 0; i < stamps_ns.size(); ++i) {
    const double dt = i == 0 ? 0 : time_s(stamps_ns[i]) - time_s(stamps_ns[i - 1]);
    e.clock_m += e.drift_mps * dt;
    e.ionosphere_m = gauss_markov(e.ionosphere_m, i == 0, dt, m.ionosphere_sigma_m, m.atmosphere_tau_s, e);
    const double t_rx = m.sky_epoch_s + time_s(stamps_ns[i]);
    const Eigen::Vector3d rx_ecef = frame.to_ecef(p_W[i]);
    Epoch epoch{t_rx, {}};
    for (const OrbitElements& orbit : almanac) {
      Pseudorange p;
      bool los = true;
      if (!observe(orbit, rx_ecef, t_rx, frame, tracer, p_W[i], dt, m, e, &p, &los)) continue;
      epoch.observations.push_back(p);
      out.pseudoranges.push_back(PseudorangeRow{stamps_ns[i], p.satellite_id, static_cast<int>(p.system), p.range_m,
                                                p.satellite_ecef, p.elevation_deg, p.cn0_dbhz, los});
    }
    ++out.epochs;
    const Fix fix = solve_fix(epoch, guess, receiver);
    if (!fix.valid) continue;
    guess = fix.p_ecef;
    out.fixes.push_back(to_sample(fix, stamps_ns[i], p_W[i], frame));
  }
  return out;
}

void write_pseudoranges(const std::filesystem::path& dir, const std::vector<PseudorangeRow>& rows) {
  const std::filesystem::path file = dir / "mav0" / "gnss0" / "pseudoranges.csv";
  std::ofstream out(file);
  if (!out) throw InputError(file.string() + ": cannot write");
  out << "#timestamp [ns],satellite_id,system (1 GPS 8 Galileo),pseudorange [m],sat_x [m],sat_y [m],sat_z [m],"
         "elevation [deg],cn0 [dB-Hz],line_of_sight\n";
  char line[256];
  for (const PseudorangeRow& r : rows) {
    std::snprintf(line, sizeof line, "%lld,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.2f,%d\n",
                  static_cast<long long>(r.stamp_ns), r.satellite_id, r.system, r.pseudorange_m, r.sat_ecef.x(),
                  r.sat_ecef.y(), r.sat_ecef.z(), r.elevation_deg, r.cn0_dbhz, r.line_of_sight ? 1 : 0);
    out << line;
  }
  if (!out) throw InputError(file.string() + ": write failed");
}

}  // namespace twinslam::sim
