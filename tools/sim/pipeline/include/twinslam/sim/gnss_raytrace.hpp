#pragma once
// `gnss.model: raytrace`: urban GNSS from the city's geometry (issue 13, part 2). Per epoch (at gnss.rate_hz) and per
// GPS/Galileo satellite above the mask (nominal constellations, common/gnss), the world mesh decides with Embree
// (SignalTracer) whether the signal arrives directly, directly and by a single-bounce facade reflection (code
// multipath: the early-late correlator is pulled by the reflected copy), only by the reflection (NLOS: the whole extra
// path, a weaker signal) or not at all (dropped). The pseudorange adds the receiver clock (bias and drift, one
// inter-system offset for Galileo), the residual atmosphere (one vertical ionospheric residual over the receiver,
// mapped to each satellite by the thin-shell obliquity, plus a small part of its own per satellite; Gauss-Markov in
// time) and C/N0-dependent tracking noise. The same receiver as `twinslam gnss solve` (weighted least squares, fault exclusion, no truth in
// its initial guess) turns each epoch into the fix written to gnss0/data.csv; epochs with too few signals give none.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/gnss_sim.hpp"
#include "twinslam/sim/world/embree_scene.hpp"

namespace twinslam::sim {

// The model's constants (not scenario keys yet; units in the comments).
struct RaytraceGnssModel {
  double sky_epoch_s = 0;              // time of the sky at simulation time 0 [s since the almanac epoch]
  double elevation_mask_deg = 10;      // satellites below are not tracked [deg]
  double clock_bias_max_m = 3e5;       // initial receiver clock bias, uniform in +-this [m] (1 ms)
  double clock_drift_sigma_mps = 30;   // receiver clock drift (TCXO, 1e-7) [m/s]
  double galileo_offset_m = 2.5;       // Galileo-to-GPS system time offset as the receiver sees it [m]
  double ionosphere_sigma_m = 1.5;     // vertical ionospheric residual after the single-frequency broadcast (Klobuchar)
                                       // correction, which removes about half of it [m]
  double per_satellite_sigma_m = 1.0;  // what is each satellite's own at zenith: broadcast orbit and clock errors
                                       // (URE ~0.7 m), ionospheric gradients between pierce points, troposphere
                                       // model error (mapped by 1 / sin(elevation)) [m]
  double atmosphere_tau_s = 300;       // correlation time of both [s]
  double reflection_loss_min_db = 3;   // power lost in a facade reflection, uniform in [min, max] per signal: glass
  double reflection_loss_max_db = 12;  // and metal reflect well, brick and concrete less [dB]
  // Code multipath with a narrow correlator (early-late spacing 0.2 chip of GPS C/A): a reflected copy delayed by
  // delta pulls the code loop by alpha min(delta, this) cos(phi) / (1 + alpha cos(phi)), alpha its relative
  // amplitude, phi its carrier phase (uniform: 19 cm of path change turn it once, so it is new at every epoch); copies
  // delayed by more than 1.1 chip do not overlap the correlator and pull nothing [m].
  double correlator_half_spacing_m = 29.3;
  double noise_at_45dbhz_m = 0.3;      // code tracking noise at 45 dB-Hz; x 10^((45 - C/N0)/20) [m]
};

struct PseudorangeRow {
  std::int64_t stamp_ns = 0;
  int satellite_id = 0;
  int system = 1;                      // 1 GPS, 8 Galileo (smartLoc / RTKLIB numbering)
  double pseudorange_m = 0;
  Eigen::Vector3d sat_ecef = Eigen::Vector3d::Zero();  // at transmission [m, ECEF]
  double elevation_deg = 0, cn0_dbhz = 0;
  bool line_of_sight = true;
};

struct RaytraceGnss {
  std::vector<GnssSample> fixes;       // epochs with a fix
  std::vector<PseudorangeRow> pseudoranges;
  std::size_t epochs = 0;              // epochs simulated (fixes.size() <= epochs)
};

// At stamps_ns with the true antenna positions p_W (W = ENU at origin); deterministic in `seed`.
RaytraceGnss simulate_gnss_raytrace(const std::vector<std::int64_t>& stamps_ns,
                                    const std::vector<Eigen::Vector3d>& p_W, const Origin& origin,
                                    const EmbreeScene& world, std::uint64_t seed, const RaytraceGnssModel& model = {});

// DIR/mav0/gnss0/pseudoranges.csv (CONTRACTS.md).
void write_pseudoranges(const std::filesystem::path& dir, const std::vector<PseudorangeRow>& rows);

}  // namespace twinslam::sim
