#include "twinslam/sim/gnss_raytrace.hpp"

#include <cstdio>
#include <fstream>
#include <random>

#include "gnss_signal_model.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/gnss/constellation.hpp"
#include "twinslam/gnss/receiver.hpp"
#include "twinslam/sim/clock.hpp"

namespace twinslam::sim {
namespace {

using namespace twinslam::gnss;
using namespace twinslam::sim::gnss_model;

// One satellite's pseudorange at one epoch, or none if the signal cannot reach the receiver.
bool observe(const OrbitElements& orbit, const Eigen::Vector3d& rx_ecef, double t_rx, const LocalFrame& frame,
             const SignalTracer& tracer, const Eigen::Vector3d& p_W, double dt_s, const RaytraceGnssModel& m,
             ErrorState& e, Pseudorange* out, bool* los) {
  const SatelliteLook s = look_at(orbit, rx_ecef, t_rx);
  if (s.look.elevation_deg < m.elevation_mask_deg) return false;
  const SignalPath path = tracer.trace(p_W, frame.R_W_ECEF * (s.sat_rx_ecef - rx_ecef).normalized(), true);
  if (!path.line_of_sight && !path.reflected) return false;
  double cn0 = draw_direct_cn0_dbhz(s.look.elevation_deg, e);
  const double path_error = reflection_error(path, m, e, &cn0);
  *out = make_pseudorange(orbit, s, path_error, cn0, dt_s, m, e);
  *los = path.line_of_sight;
  return true;
}

}  // namespace

RaytraceGnss simulate_gnss_raytrace(const std::vector<std::int64_t>& stamps_ns,
                                    const std::vector<Eigen::Vector3d>& p_W, const Origin& origin,
                                    const EmbreeScene& world, std::uint64_t seed, const RaytraceGnssModel& m) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32), 4u};
  ErrorState e(seq);
  start_clock(m, e);
  const LocalFrame frame(origin);
  const SignalTracer tracer(world);
  const std::vector<OrbitElements> almanac = nominal_constellation();
  return run_receiver_epochs(stamps_ns, p_W, frame, m, e,
                             [&](std::size_t i, double dt, double t_rx, const Eigen::Vector3d& rx_ecef, Epoch& epoch,
                                 RaytraceGnss& out) {
                               for (const OrbitElements& orbit : almanac) {
                                 Pseudorange p;
                                 bool los = true;
                                 if (!observe(orbit, rx_ecef, t_rx, frame, tracer, p_W[i], dt, m, e, &p, &los)) continue;
                                 epoch.observations.push_back(p);
                                 out.pseudoranges.push_back(to_row(stamps_ns[i], p, los));
                               }
                             });
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
