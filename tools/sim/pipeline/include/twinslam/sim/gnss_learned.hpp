#pragma once
// `gnss.model: learned`: the paper's data-driven GNSS generator (Merat et al. 2025, Sec. IV-A; issue 13, item 4).
//
// 1. Training data: random positions within 20 m of the flight's track, outside every building footprint, heights
//    from the ground to above the tallest roof, sky times within the flight, each ray-traced with the physics of
//    `gnss.model: raytrace` (SignalTracer and gnss_signal_model): which satellites above the mask are received
//    (directly, with a facade reflection, or only by the reflection: NLOS), and per received signal the range error
//    its reflection causes and its C/N0 relative to a direct signal; plus the receiver's fix at each position (for
//    the figure).
// 2. Models, fitted with the scenario's seed: a Gaussian process of the number of signals received against the
//    height above ground (learn/gaussian_process.hpp); a Gaussian mixture by EM over (height, elevation, range error
//    as sign(e) ln(1 + |e|), C/N0 offset) (learn/gaussian_mixture.hpp; in metres the NLOS errors are heavy-tailed
//    and the Gaussian components' tails gave 120 m errors where the training data's 99th percentile is 90 m), from
//    which a signal's error and C/N0 are drawn given the height and the satellite's elevation (the paper conditions
//    on height only; the elevation is added because the ray-traced NLOS signals are the low ones, 47 % of the
//    received signals below 20 deg on city-loops against 1 % above 50 deg, and a range error moves the fix far more,
//    and is weighted far more, on a high satellite than on a low one); each component carries the share of NLOS
//    signals among the training signals it explains; and the share of the satellites above the mask that are
//    received, per 5 m height bin and 10 deg elevation bin.
// 3. Generation along the flight, per epoch: n from the GP at the flight height (mean plus its predictive standard
//    deviation times a standard normal that is Gauss-Markov in time), rounded, clamped to the satellites above the
//    mask; which n: each with a probability proportional to the received share at its height and elevation, scaled
//    to sum to n (Pareto order sampling; inclusion_probabilities; buildings do not take only the lowest satellites:
//    on city-loops 53 % of those below 20 deg are received and 72-77 % of those above, so "highest elevations first"
//    would drop nearly every low, NLOS-prone signal), with persistent keys so the chosen set changes as slowly as
//    the ray-traced one; per chosen satellite an error and C/N0 offset from the mixture given (height, elevation),
//    kept correlated in time (its component held, its draw within the component Gauss-Markov), clamped to the range
//    of the training errors; then the raytrace model's satellite atmosphere, ionosphere, tracking noise and receiver
//    clock, and the same receiver makes the fix. The correlation times are those of the ray-traced data along
//    city-loops (count: 5 s, errors: 8 s; autocorrelation 0.83 / 0.85 at 1 s, 0.37 / 0.54 at 5 s).
// The fitted models are stored with the dataset (mav0/gnss0/learned_model.yaml, layout in docs/CONTRACTS.md) and
// drawn in mav0/gnss0/gnss_vs_height.png (the paper's Fig. 6).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/gnss_raytrace.hpp"
#include "twinslam/sim/learn/gaussian_mixture.hpp"
#include "twinslam/sim/learn/gaussian_process.hpp"
#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

// Where and how many training positions (constants of the model, not scenario keys).
struct GnssTrainingConfig {
  std::size_t positions = 1500;
  double min_height_m = 0.5;            // above ground [m]
  double height_margin_m = 10;          // heights up to the tallest roof top plus this [m]
  double footprint_margin_m = 1.0;      // positions keep this far outside every building footprint [m]
  // Positions lie within this horizontal distance of the flight's track [m]; 0 or less takes the whole city
  // (the paper's choice; see run_learned_gnss for why the default is the track's neighbourhood).
  double track_radius_m = 20;
};

// One received signal of the training data.
struct TrainingSignal {
  std::size_t position = 0;             // index of its position
  double height_m = 0;                  // of the receiver above ground [m]
  double elevation_deg = 0;
  double error_m = 0;                   // range error of the reflection: NLOS extra path or code multipath [m]
  double cn0_offset_db = 0;             // C/N0 minus that of a direct signal at this elevation (noise included) [dB]
  bool line_of_sight = true;
};

// One satellite above the mask at a training position.
struct TrainingSatellite {
  std::size_t position = 0;
  double elevation_deg = 0;
  bool received = false;
};

struct GnssTrainingData {
  std::vector<Eigen::Vector3d> positions_W;  // [m, W]
  std::vector<double> heights_m;             // above ground [m]
  std::vector<double> sky_time_s;            // sky time of each position [s since the almanac epoch]
  std::vector<int> received;                 // signals received at each position
  std::vector<double> fix_horizontal_m;      // horizontal error of the receiver's fix there (NaN: no fix) [m]
  std::vector<TrainingSignal> signals;
  std::vector<TrainingSatellite> sky;        // every satellite above the mask at every position
  double elevation_mask_deg = 10;            // of the ray tracing [deg]
};

// Uniform random positions in area_W = [min e, min n, max e, max n] outside the footprints (with the margin), heights
// uniform in [min_height_m, tallest top + height_margin_m] above hints.ground_z_m; deterministic in seed.
std::vector<Eigen::Vector3d> random_city_positions(const SceneHints& hints, const std::array<double, 4>& area_W,
                                                   const GnssTrainingConfig& config, std::uint64_t seed);

// Random positions within config.track_radius_m of the track's points (one drawn uniformly per position, so where the
// flight spends its time), outside the footprints (with the margin) and within hints.extent_W, heights as
// random_city_positions; deterministic in seed.
std::vector<Eigen::Vector3d> random_track_positions(const SceneHints& hints, const std::vector<Eigen::Vector3d>& track_W,
                                                    const GnssTrainingConfig& config, std::uint64_t seed);

// Ray-traces every position at its sky time (RaytraceGnssModel physics: mask, line of sight, reflections, their
// errors and C/N0, and each position's fix); deterministic in seed.
GnssTrainingData trace_training_data(const std::vector<Eigen::Vector3d>& positions_W,
                                     const std::vector<double>& sky_time_s, double ground_z_m, const Origin& origin,
                                     const EmbreeScene& world, std::uint64_t seed,
                                     const RaytraceGnssModel& model = {});

// How the fitted models are used along a flight.
struct LearnedGenerationConfig {
  double count_tau_s = 5;      // correlation time of the satellite count's deviation and of the choice [s]
  double error_tau_s = 8;      // of a satellite's error: how long it keeps its component, its draw's Gauss-Markov [s]
};

inline constexpr double kElevationBinDeg = 10;
inline constexpr double kShareHeightBinM = 5;        // height bins of received_share, from the ground up [m]
inline constexpr double kSharePriorSatellites = 5;   // weight of a received_share cell's prior [satellites]

struct LearnedGnssModel {
  learn::GaussianProcess satellites;            // number of signals received vs height above ground [m]
  // Over (height [m], elevation [deg], range error [m], C/N0 offset [dB]); drawn given the first two.
  learn::GaussianMixture errors{};
  std::vector<double> nlos_share{};               // per component of `errors`: NLOS share of its training signals
  // Share of the satellites above the mask that were received, per height bin of kShareHeightBinM from the ground up
  // (rows; the last is open above) and elevation bin of kElevationBinDeg from the mask up (columns; the last ends at
  // 90 deg): the weights of the choice of satellites (received_share_at).
  std::vector<std::vector<double>> received_share{};
  std::array<double, 2> error_range_m{0, 0};    // of the training signals: drawn errors are clamped to it
  std::array<double, 2> cn0_offset_range_db{0, 0};
  LearnedGenerationConfig generation{};
  // What it was trained on (recorded in the file).
  std::size_t training_positions = 0, training_signals = 0;
  std::array<double, 4> area_W{0, 0, 0, 0};
  std::array<double, 2> height_range_m{0, 0};
  std::array<double, 2> sky_time_s{0, 0};
  double elevation_mask_deg = 10;
  std::uint64_t seed = 0;
};

struct LearnedFitConfig {
  std::size_t gp_max_points = 250;
  int gmm_components = 16;
  std::size_t gmm_max_signals = 8000;           // random subsample of the signals for EM
};

// Fits the models (seeded). Throws InputError when the training data are too few for them.
LearnedGnssModel fit_learned_gnss(const GnssTrainingData& data, std::uint64_t seed,
                                  const LearnedFitConfig& config = {});

// The mixture models a signal's range error e as sign(e) ln(1 + |e| / 1 m), and back.
double error_to_log(double error_m);
double error_from_log(double log_error);

// The share of the satellites above the mask that were received, per (height bin, elevation bin). Per height because
// the low satellites are the ones the buildings take near the ground (city-loops: 35 % of those at 10-20 deg are
// received below 5 m, 84 % above 20 m), so one share for all heights gives a low flight too many low, NLOS-prone
// signals. A cell's share is shrunk toward its elevation bin's share over all heights by kSharePriorSatellites
// pseudo-satellites (a Beta prior), so thinly sampled cells stay near it.
std::vector<std::vector<double>> received_share_table(const GnssTrainingData& data);

// received_share at this height above ground and elevation: linear in height between the height bins' centres.
double received_share_at(const LearnedGnssModel& model, double height_m, double elevation_deg);

// The probability that each satellite in view is among the n received: proportional to its share, summing to n, at
// most 1 (those capped are received for sure and the others scaled up). Drawing n of them "weighted by the share"
// without replacement (Efraimidis-Spirakis) is not that: with 9 of 12 taken, a satellite of share 0.36 came out at
// 70 % of the rate of one of 0.87, where the ray tracer has 41 %.
std::vector<double> inclusion_probabilities(const std::vector<double>& shares, std::size_t n);
// Pareto order sampling (Rosen 1997): taking the n smallest of u (1 - pi) / ((1 - u) pi), u uniform, includes each
// with probability close to its pi (exactly 1 and 0 at the ends); u is a satellite's persistent key.
double pareto_rank(double u, double pi);

// mav0/gnss0/learned_model.yaml and back (layout in docs/CONTRACTS.md). read_: InputError naming the file.
void write_learned_model(const std::filesystem::path& file, const LearnedGnssModel& model);
LearnedGnssModel read_learned_model(const std::filesystem::path& file);

// The learned generator at stamps_ns with the true antenna positions p_W (heights above ground_z_m): the same outputs
// as simulate_gnss_raytrace (fixes; pseudoranges with line_of_sight = the drawn component's NLOS share is below one
// half); deterministic in seed.
RaytraceGnss simulate_gnss_learned(const std::vector<std::int64_t>& stamps_ns, const std::vector<Eigen::Vector3d>& p_W,
                                   double ground_z_m, const Origin& origin, const LearnedGnssModel& learned,
                                   std::uint64_t seed, const RaytraceGnssModel& model = {});

// What `twinslam sim` does for `gnss.model: learned`: training positions in the flight's neighbourhood at sky times
// within the flight, the fit, the generation, and the files in DIR/mav0/gnss0 (learned_model.yaml, pseudoranges.csv,
// gnss_vs_height.png). Returns the generated data.
RaytraceGnss run_learned_gnss(const std::filesystem::path& dir, const std::vector<std::int64_t>& stamps_ns,
                              const std::vector<Eigen::Vector3d>& p_W, const SceneHints& hints, const Origin& origin,
                              const EmbreeScene& world, std::uint64_t seed, const GnssTrainingConfig& training = {});

// The paper's Fig. 6 for this model, three panels against the height above ground: signals received (training
// samples, GP mean and +-2 sigma), the range error of a signal (training samples, the mixture's median and 5-95 %
// band), and the horizontal error of the fix (ray-traced at the training positions, learned along the flight).
void write_gnss_vs_height_png(const std::filesystem::path& png, const GnssTrainingData& training,
                              const LearnedGnssModel& model, const std::vector<GnssSample>& fixes, double ground_z_m);

}  // namespace twinslam::sim
