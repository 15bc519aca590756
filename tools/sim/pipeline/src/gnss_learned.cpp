#include "twinslam/sim/gnss_learned.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <random>
#include <string>

#include "gnss_signal_model.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/gnss/constellation.hpp"
#include "twinslam/gnss/receiver.hpp"
#include "twinslam/sim/clock.hpp"

namespace twinslam::sim {
namespace {

using namespace twinslam::gnss;
using namespace twinslam::sim::gnss_model;

// Independent random streams of one seed (the raytrace model's own stream is {seed, 4}).
std::seed_seq stream(std::uint64_t seed, std::uint32_t which) {
  return std::seed_seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32), which};
}
constexpr std::uint32_t kStreamPhysics = 5, kStreamDraws = 6, kStreamPositions = 7, kStreamTrace = 8,
                        kStreamFit = 9, kStreamSkyTimes = 10;

bool inside_footprint(const SceneHints& hints, double e, double n, double margin) {
  for (const BuildingHint& b : hints.buildings) {
    for (const Eigen::Vector4d& r : b.rects_W) {
      if (e > r[0] - margin && e < r[2] + margin && n > r[1] - margin && n < r[3] + margin) return true;
    }
  }
  return false;
}

double tallest_top_m(const SceneHints& hints) {
  double top = hints.tall_building_height_m;
  for (const BuildingHint& b : hints.buildings) top = std::max(top, b.top_m);
  return top;
}

}  // namespace

namespace {

// config.positions positions outside the footprints (with the margin): a horizontal position from `draw`, then a
// height from the ground to the tallest roof plus the margin, kept when `allowed` says so; `what` names the area in
// the error when it is (almost) all buildings.
template <typename Draw, typename Allowed>
std::vector<Eigen::Vector3d> sample_positions(const SceneHints& hints, const GnssTrainingConfig& config,
                                              std::uint64_t seed, Draw draw, Allowed allowed, const char* what) {
  std::seed_seq seq = stream(seed, kStreamPositions);
  std::mt19937_64 rng(seq);
  std::uniform_real_distribution<double> uh(config.min_height_m, tallest_top_m(hints) + config.height_margin_m);
  std::vector<Eigen::Vector3d> out;
  for (std::size_t tries = 0; out.size() < config.positions; ++tries) {
    if (tries > 100 * config.positions + 1000) {
      throw InputError(std::string("gnss.model learned: ") + what + " is (almost) all buildings");
    }
    const Eigen::Vector2d en = draw(rng);
    const double h = uh(rng);
    if (!allowed(en) || inside_footprint(hints, en.x(), en.y(), config.footprint_margin_m)) continue;
    out.emplace_back(en.x(), en.y(), hints.ground_z_m + h);
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> random_city_positions(const SceneHints& hints, const std::array<double, 4>& area_W,
                                                   const GnssTrainingConfig& config, std::uint64_t seed) {
  if (!(area_W[2] > area_W[0]) || !(area_W[3] > area_W[1])) {
    throw InputError("gnss.model learned: the training area is empty");
  }
  std::uniform_real_distribution<double> ue(area_W[0], area_W[2]), un(area_W[1], area_W[3]);
  const auto draw = [&](std::mt19937_64& rng) {
    const double e = ue(rng);
    return Eigen::Vector2d(e, un(rng));
  };
  return sample_positions(hints, config, seed, draw, [](const Eigen::Vector2d&) { return true; }, "the training area");
}

std::vector<Eigen::Vector3d> random_track_positions(const SceneHints& hints, const std::vector<Eigen::Vector3d>& track_W,
                                                    const GnssTrainingConfig& config, std::uint64_t seed) {
  if (track_W.empty() || !(config.track_radius_m > 0)) throw InputError("gnss.model learned: no track to train along");
  std::uniform_int_distribution<std::size_t> which(0, track_W.size() - 1);
  std::uniform_real_distribution<double> unit(0, 1);
  // A point of the track, then uniform in the disc of track_radius_m around it.
  const auto draw = [&](std::mt19937_64& rng) {
    const Eigen::Vector3d& c = track_W[which(rng)];
    const double r = config.track_radius_m * std::sqrt(unit(rng));
    const double a = 2 * std::numbers::pi * unit(rng);
    return Eigen::Vector2d(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
  };
  const std::array<double, 4>& x = hints.extent_W;
  const auto inside_city = [&](const Eigen::Vector2d& p) {
    return p.x() >= x[0] && p.x() <= x[2] && p.y() >= x[1] && p.y() <= x[3];
  };
  return sample_positions(hints, config, seed, draw, inside_city, "the track's neighbourhood");
}

GnssTrainingData trace_training_data(const std::vector<Eigen::Vector3d>& positions_W,
                                     const std::vector<double>& sky_time_s, double ground_z_m, const Origin& origin,
                                     const EmbreeScene& world, std::uint64_t seed, const RaytraceGnssModel& m) {
  if (positions_W.size() != sky_time_s.size()) {
    throw InputError("gnss.model learned: " + std::to_string(positions_W.size()) + " training positions but " +
                     std::to_string(sky_time_s.size()) + " times");
  }
  std::seed_seq seq = stream(seed, kStreamTrace);
  ErrorState e(seq);
  const LocalFrame frame(origin);
  const SignalTracer tracer(world);
  const std::vector<OrbitElements> almanac = nominal_constellation();
  const ReceiverConfig receiver;
  GnssTrainingData d;
  d.elevation_mask_deg = m.elevation_mask_deg;
  d.positions_W = positions_W;
  d.sky_time_s = sky_time_s;
  for (std::size_t i = 0; i < positions_W.size(); ++i) {
    const Eigen::Vector3d rx_ecef = frame.to_ecef(positions_W[i]);
    const double h = positions_W[i].z() - ground_z_m;
    d.heights_m.push_back(h);
    // Each position is a first epoch of its own: fresh clock, atmosphere from its stationary distribution.
    e.satellite_m.clear();
    start_clock(m, e);
    advance_epoch(true, 0, m, e);
    Epoch epoch{sky_time_s[i], {}};
    int received = 0;
    for (const OrbitElements& orbit : almanac) {
      const SatelliteLook s = look_at(orbit, rx_ecef, sky_time_s[i]);
      if (s.look.elevation_deg < m.elevation_mask_deg) continue;
      const SignalPath path =
          tracer.trace(positions_W[i], frame.R_W_ECEF * (s.sat_rx_ecef - rx_ecef).normalized(), true);
      const bool arrives = path.line_of_sight || path.reflected;
      d.sky.push_back({i, s.look.elevation_deg, arrives});
      if (!arrives) continue;
      ++received;
      const double nominal = nominal_cn0_dbhz(s.look.elevation_deg);
      double cn0 = draw_direct_cn0_dbhz(s.look.elevation_deg, e);
      TrainingSignal t;
      t.position = i;
      t.height_m = h;
      t.elevation_deg = s.look.elevation_deg;
      t.error_m = reflection_error(path, m, e, &cn0);
      t.cn0_offset_db = cn0 - nominal;
      t.line_of_sight = path.line_of_sight;
      d.signals.push_back(t);
      epoch.observations.push_back(make_pseudorange(orbit, s, t.error_m, cn0, 0, m, e));
    }
    d.received.push_back(received);
    const Fix fix = solve_fix(epoch, Eigen::Vector3d::Zero(), receiver);
    d.fix_horizontal_m.push_back(fix.valid ? (frame.to_W(fix.p_ecef) - positions_W[i]).head<2>().norm()
                                           : std::numeric_limits<double>::quiet_NaN());
  }
  return d;
}

LearnedGnssModel fit_learned_gnss(const GnssTrainingData& data, std::uint64_t seed, const LearnedFitConfig& config) {
  if (data.signals.empty()) throw InputError("gnss.model learned: no signal was received at any training position");
  learn::GpFitOptions gp;
  gp.max_points = config.gp_max_points;
  LearnedGnssModel model{.satellites = learn::GaussianProcess::fit(
                              data.heights_m, std::vector<double>(data.received.begin(), data.received.end()), gp)};
  // The mixture over (height, elevation, error, C/N0 offset), on a seeded subsample of the signals.
  std::vector<std::size_t> idx(data.signals.size());
  std::iota(idx.begin(), idx.end(), 0);
  if (idx.size() > config.gmm_max_signals) {
    std::seed_seq seq = stream(seed, kStreamFit);
    std::mt19937_64 rng(seq);
    std::shuffle(idx.begin(), idx.end(), rng);
    idx.resize(config.gmm_max_signals);
    std::sort(idx.begin(), idx.end());
  }
  Eigen::MatrixXd X(static_cast<Eigen::Index>(idx.size()), 4);
  for (std::size_t r = 0; r < idx.size(); ++r) {
    const TrainingSignal& s = data.signals[idx[r]];
    X.row(static_cast<Eigen::Index>(r)) << s.height_m, s.elevation_deg, error_to_log(s.error_m), s.cn0_offset_db;
  }
  learn::GmmFitOptions o;
  o.components = config.gmm_components;
  o.seed = seed;
  o.tolerance = 1e-5;  // nats per point: the last digits of the likelihood change nothing drawn from it
  o.max_iterations = 200;
  model.errors = learn::GaussianMixture::fit(X, o);
  // Each component's share of NLOS signals (responsibility-weighted).
  const std::size_t K = model.errors.components().size();
  std::vector<double> nlos(K, 0.0), total(K, 0.0);
  for (std::size_t r = 0; r < idx.size(); ++r) {
    const Eigen::VectorXd g = model.errors.responsibilities(X.row(static_cast<Eigen::Index>(r)).transpose());
    const bool is_nlos = !data.signals[idx[r]].line_of_sight;
    for (std::size_t k = 0; k < K; ++k) {
      total[k] += g[static_cast<Eigen::Index>(k)];
      nlos[k] += is_nlos ? g[static_cast<Eigen::Index>(k)] : 0.0;
    }
  }
  // Shares below 1e-9 are underflowed responsibilities (1e-310 in the file otherwise): none of the component's signals.
  for (std::size_t k = 0; k < K; ++k) {
    const double share = total[k] > 0 ? nlos[k] / total[k] : 0.0;
    model.nlos_share.push_back(share < 1e-9 ? 0.0 : share);
  }
  model.error_range_m = {error_from_log(X.col(2).minCoeff()), error_from_log(X.col(2).maxCoeff())};
  model.cn0_offset_range_db = {X.col(3).minCoeff(), X.col(3).maxCoeff()};
  model.received_share = received_share_table(data);
  model.elevation_mask_deg = data.elevation_mask_deg;
  model.training_positions = data.positions_W.size();
  model.training_signals = data.signals.size();
  const auto [hlo, hhi] = std::minmax_element(data.heights_m.begin(), data.heights_m.end());
  model.height_range_m = {*hlo, *hhi};
  const auto [tlo, thi] = std::minmax_element(data.sky_time_s.begin(), data.sky_time_s.end());
  model.sky_time_s = {*tlo, *thi};
  if (!data.positions_W.empty()) {
    model.area_W = {data.positions_W[0].x(), data.positions_W[0].y(), data.positions_W[0].x(),
                    data.positions_W[0].y()};
    for (const Eigen::Vector3d& p : data.positions_W) {
      model.area_W = {std::min(model.area_W[0], p.x()), std::min(model.area_W[1], p.y()),
                      std::max(model.area_W[2], p.x()), std::max(model.area_W[3], p.y())};
    }
  }
  model.seed = seed;
  return model;
}

RaytraceGnss simulate_gnss_learned(const std::vector<std::int64_t>& stamps_ns, const std::vector<Eigen::Vector3d>& p_W,
                                   double ground_z_m, const Origin& origin, const LearnedGnssModel& learned,
                                   std::uint64_t seed, const RaytraceGnssModel& m) {
  if (stamps_ns.size() != p_W.size()) throw InputError("gnss.model learned: stamps and positions differ in number");
  if (learned.errors.dimension() != 4 || learned.nlos_share.size() != learned.errors.components().size()) {
    throw InputError("gnss.model learned: the error model is not over (height, elevation, error, C/N0 offset)");
  }
  std::seed_seq physics_seq = stream(seed, kStreamPhysics);
  ErrorState e(physics_seq);
  start_clock(m, e);
  std::seed_seq draws_seq = stream(seed, kStreamDraws);
  std::mt19937_64 rng(draws_seq);
  std::normal_distribution<double> normal(0, 1);
  std::uniform_real_distribution<double> uniform(0, 1);
  const LocalFrame frame(origin);
  const std::vector<OrbitElements> almanac = nominal_constellation();
  const LearnedGenerationConfig& g = learned.generation;

  // Per satellite: its choice key (a standard normal, Gauss-Markov in time) and, while received, its mixture
  // component and standard-normal draw within it.
  struct SatelliteState {
    double key = 0;
    std::size_t last_seen = 0;
    bool received = false;
    int component = 0;
    bool nlos = false;   // the flag written to pseudoranges.csv, drawn with the component
    Eigen::Vector2d w = Eigen::Vector2d::Zero();
  };
  std::map<std::pair<int, int>, SatelliteState> states;
  double z_count = normal(rng);  // the count's deviation from the GP mean, in its predictive standard deviations

  const auto observe = [&](std::size_t i, double dt, double t_rx, const Eigen::Vector3d& rx_ecef, Epoch& epoch,
                           RaytraceGnss& out) {
    const double keep_count = i == 0 ? 0 : std::exp(-dt / g.count_tau_s);
    const double keep_error = i == 0 ? 0 : std::exp(-dt / g.error_tau_s);
    const auto step = [&](double x, double keep) { return keep * x + std::sqrt(1 - keep * keep) * normal(rng); };
    // The satellites above the mask, each with its choice key u = Phi(key), uniform and persistent.
    struct InView {
      const OrbitElements* orbit;
      SatelliteLook look;
      SatelliteState* state;
      double u, share, rank = 0;
    };
    const double h = p_W[i].z() - ground_z_m;
    std::vector<InView> sky;
    for (const OrbitElements& orbit : almanac) {
      const SatelliteLook s = look_at(orbit, rx_ecef, t_rx);
      if (s.look.elevation_deg < m.elevation_mask_deg) continue;
      const auto id = std::make_pair(static_cast<int>(orbit.system), orbit.id);
      const auto it = states.find(id);
      const bool continuing = it != states.end() && i > 0 && it->second.last_seen == i - 1;
      SatelliteState& st = states[id];
      if (!continuing) st.received = false;
      st.key = continuing ? step(st.key, keep_count) : normal(rng);
      st.last_seen = i;
      const double u = std::clamp(0.5 * std::erfc(-st.key / std::sqrt(2.0)), 1e-300, 1 - 1e-16);
      sky.push_back({&orbit, s, &st, u, received_share_at(learned, h, s.look.elevation_deg)});
    }
    // How many: the GP at this height.
    const learn::GpPrediction count = learned.satellites.predict(h);
    if (i > 0) z_count = step(z_count, keep_count);
    const std::size_t n = static_cast<std::size_t>(std::clamp(
        std::lround(count.mean + std::sqrt(count.var_y) * z_count), 0L, static_cast<long>(sky.size())));
    // Which: Pareto order sampling takes the n smallest ranks, each satellite with probability close to its target
    // (the shares scaled to sum to n; inclusion_probabilities).
    std::vector<double> shares;
    for (const InView& v : sky) shares.push_back(v.share);
    const std::vector<double> pi = inclusion_probabilities(shares, n);
    for (std::size_t j = 0; j < sky.size(); ++j) sky[j].rank = pareto_rank(sky[j].u, pi[j]);
    std::stable_sort(sky.begin(), sky.end(), [](const InView& a, const InView& b) { return a.rank < b.rank; });
    for (std::size_t j = 0; j < sky.size(); ++j) {
      SatelliteState& st = *sky[j].state;
      if (j >= n) {
        st.received = false;
        continue;
      }
      const SatelliteLook& s = sky[j].look;
      const learn::GaussianMixture given = learned.errors.conditional(Eigen::Vector2d(h, s.look.elevation_deg));
      const auto draw_component = [&] {
        st.component = given.sample_component(rng);
        st.nlos = uniform(rng) < learned.nlos_share[static_cast<std::size_t>(st.component)];
      };
      if (!st.received) {
        draw_component();
        st.w = Eigen::Vector2d(normal(rng), normal(rng));
      } else {
        if (uniform(rng) >= keep_error) draw_component();
        st.w = Eigen::Vector2d(step(st.w.x(), keep_error), step(st.w.y(), keep_error));
      }
      st.received = true;
      const std::size_t k = static_cast<std::size_t>(st.component);
      const Eigen::VectorXd x = given.components()[k].mean + given.cholesky(k) * st.w;
      const double error = std::clamp(error_from_log(x[0]), learned.error_range_m[0], learned.error_range_m[1]);
      const double cn0 = nominal_cn0_dbhz(s.look.elevation_deg) +
                         std::clamp(x[1], learned.cn0_offset_range_db[0], learned.cn0_offset_range_db[1]);
      const Pseudorange p = make_pseudorange(*sky[j].orbit, s, error, cn0, dt, m, e);
      epoch.observations.push_back(p);
      out.pseudoranges.push_back(to_row(stamps_ns[i], p, !st.nlos));
    }
  };
  return run_receiver_epochs(stamps_ns, p_W, frame, m, e, observe);
}

RaytraceGnss run_learned_gnss(const std::filesystem::path& dir, const std::vector<std::int64_t>& stamps_ns,
                              const std::vector<Eigen::Vector3d>& p_W, const SceneHints& hints, const Origin& origin,
                              const EmbreeScene& world, std::uint64_t seed, const GnssTrainingConfig& training) {
  // Training positions near the track: the model knows only the height, so it describes the streets it was trained
  // in. Over the whole city (the paper's choice) it describes an average street, which on city-loops (at a 60 m
  // tower) gives half the ray-traced errors; over the flight's bounding box grown by 30 m (the previous choice) most
  // positions were still 20-60 m from where the drone flies, in narrower streets with longer NLOS paths (city-loops
  // 0-5 m: a 95th percentile of the range error of 32 m there, 20 m along the flight).
  const std::vector<Eigen::Vector3d> positions =
      training.track_radius_m > 0 ? random_track_positions(hints, p_W, training, seed)
                                   : random_city_positions(hints, hints.extent_W, training, seed);
  const RaytraceGnssModel physics;
  const double t0 = physics.sky_epoch_s;
  const double t1 = t0 + (stamps_ns.empty() ? 0.0 : time_s(stamps_ns.back()));
  std::seed_seq seq = stream(seed, kStreamSkyTimes);
  std::mt19937_64 rng(seq);
  std::uniform_real_distribution<double> ut(t0, std::max(t1, t0 + 1e-9));
  std::vector<double> sky_times;
  for (std::size_t i = 0; i < positions.size(); ++i) sky_times.push_back(ut(rng));
  const GnssTrainingData data =
      trace_training_data(positions, sky_times, hints.ground_z_m, origin, world, seed, physics);
  const LearnedGnssModel model = fit_learned_gnss(data, seed);
  RaytraceGnss out = simulate_gnss_learned(stamps_ns, p_W, hints.ground_z_m, origin, model, seed, physics);
  const std::filesystem::path gnss_dir = dir / "mav0" / "gnss0";
  std::filesystem::create_directories(gnss_dir);
  write_learned_model(gnss_dir / "learned_model.yaml", model);
  write_pseudoranges(dir, out.pseudoranges);
  write_gnss_vs_height_png(gnss_dir / "gnss_vs_height.png", data, model, out.fixes, hints.ground_z_m);
  return out;
}

}  // namespace twinslam::sim
