#pragma once
// The parts of the simulator's GNSS signal model that do not depend on how a signal reached the receiver (private to
// the pipeline): the receiver's clock, the atmosphere, tracking noise and the pseudorange they make, the satellite's
// geometry, the error of a facade reflection, and the fix as a GnssSample. `gnss.model: raytrace` decides with the
// ray tracer which satellites are received and how they were reflected; `gnss.model: learned` samples that from its
// fitted models; both then build the pseudoranges and fixes with these functions, so they share the physics. The
// order of the random draws is part of the raytrace output (its files are reproduced byte for byte).
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "twinslam/gnss/frames.hpp"
#include "twinslam/gnss/observation.hpp"
#include "twinslam/gnss/orbit.hpp"
#include "twinslam/gnss/receiver.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/gnss_raytrace.hpp"
#include "twinslam/sim/world/signal_tracer.hpp"

namespace twinslam::sim::gnss_model {

// The local frame W (ENU at the origin) in ECEF: p_ecef = origin_ecef + R_ECEF_W p_W (exactly what
// GeographicLib::LocalCartesian does).
struct LocalFrame {
  Eigen::Vector3d origin_ecef;
  Eigen::Matrix3d R_W_ECEF;
  explicit LocalFrame(const Origin& o);
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

// Draws the receiver clock's initial bias and drift.
void start_clock(const RaytraceGnssModel& m, ErrorState& e);
// One epoch later by dt_s (first: the first epoch): the clock drifts, the ionosphere moves on.
void advance_epoch(bool first, double dt_s, const RaytraceGnssModel& m, ErrorState& e);

// A first-order Gauss-Markov step of standard deviation sigma and correlation time tau (exact discretization); the
// first value is drawn from the stationary distribution.
double gauss_markov(double x, bool first, double dt_s, double sigma, double tau_s, ErrorState& e);

// A satellite as the receiver sees it at reception time t_rx.
struct SatelliteLook {
  gnss::SignalGeometry geometry;
  Eigen::Vector3d sat_rx_ecef = Eigen::Vector3d::Zero();  // in the ECEF frame of reception [m]
  gnss::LookAngles look;
};
SatelliteLook look_at(const gnss::OrbitElements& orbit, const Eigen::Vector3d& rx_ecef, double t_rx);

// C/N0 of a direct signal without its random part: 35 dB-Hz at the horizon, 48 at the zenith [dB-Hz].
double nominal_cn0_dbhz(double elevation_deg);
// ... and with it (1.5 dB-Hz standard deviation; one draw).
double draw_direct_cn0_dbhz(double elevation_deg, ErrorState& e);

// The range error a reflection causes, and its effect on C/N0 (cn0_dbhz is updated) [m]. NLOS: the receiver tracks
// the reflection, whole extra path, weaker. Direct + reflected: code multipath and fading (RaytraceGnssModel).
double reflection_error(const SignalPath& path, const RaytraceGnssModel& m, ErrorState& e, double* cn0_dbhz);

// The pseudorange of a received signal whose path error [m] and C/N0 are known: adds the satellite's own atmosphere
// (its Gauss-Markov state advanced by dt_s), the vertical ionosphere mapped to it, C/N0-dependent tracking noise,
// the receiver clock and the Galileo system offset.
gnss::Pseudorange make_pseudorange(const gnss::OrbitElements& orbit, const SatelliteLook& s, double path_error_m,
                                   double cn0_dbhz, double dt_s, const RaytraceGnssModel& m, ErrorState& e);

// The receiver's fix as the dataset's GNSS sample (bias_W: the fix minus the truth).
GnssSample to_sample(const gnss::Fix& fix, std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const LocalFrame& frame);

PseudorangeRow to_row(std::int64_t stamp_ns, const gnss::Pseudorange& p, bool line_of_sight);

// The epoch loop both models share: per stamp the error state advances, `observe(i, dt_s, t_rx, rx_ecef, epoch, out)`
// adds the epoch's signals (and their pseudoranges.csv rows to `out`), and the receiver solves the fix from the
// previous one, never from the truth (the Earth's centre at first). The call order keeps the random draws in order.
template <typename Observe>
RaytraceGnss run_receiver_epochs(const std::vector<std::int64_t>& stamps_ns, const std::vector<Eigen::Vector3d>& p_W,
                                 const LocalFrame& frame, const RaytraceGnssModel& m, ErrorState& e, Observe&& observe) {
  const gnss::ReceiverConfig receiver;
  RaytraceGnss out;
  Eigen::Vector3d guess = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < stamps_ns.size(); ++i) {
    const double dt = i == 0 ? 0 : time_s(stamps_ns[i]) - time_s(stamps_ns[i - 1]);
    advance_epoch(i == 0, dt, m, e);
    const double t_rx = m.sky_epoch_s + time_s(stamps_ns[i]);
    gnss::Epoch epoch{t_rx, {}};
    observe(i, dt, t_rx, frame.to_ecef(p_W[i]), epoch, out);
    ++out.epochs;
    const gnss::Fix fix = gnss::solve_fix(epoch, guess, receiver);
    if (!fix.valid) continue;
    guess = fix.p_ecef;
    out.fixes.push_back(to_sample(fix, stamps_ns[i], p_W[i], frame));
  }
  return out;
}

}  // namespace twinslam::sim::gnss_model
