// How accurate can a registration against this twin be? (issue 12: "no accepted registration wrong by more than
// 0.5 m".) For a simulated dataset (twinslam sim --features), every second of the flight: the landmarks the ideal
// tracks saw in the last H seconds, at their TRUE world positions (the simulator's surface samples, same seed),
// registered against the twin store at the TRUE keyframe pose. The correction should be zero; what it is instead is
// what the twin's own error (twin.noise_m per surface, the details it lacks) costs a registration with perfect
// landmarks: the floor under every VIO registration. Optional noise per coordinate and leaving out the landmarks on
// details (balconies, floor bands, trees, cars) separate the two causes.
// With --config, the registration config of that file (e.g. surface_error_m); the output then also says whether the
// information is consistent with these errors: the mean of xi^T W xi (the correction should be 0, so xi is its error;
// a consistent W gives the mean rank of W) and the rank correlation of the predicted position sigma with the error.
// Usage: bench_registration_floor DATASET TWIN_STORE [--horizon-s H (2)] [--noise-m N (0)] [--without-details]
//        [--config REGISTRATION.yaml]
//        (TWIN_STORE: `twinslam twin build DATASET/twin/twin.ply --origin LAT,LON,ALT --out STORE`)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/geometry/information_order.hpp"
#include "twinslam/registration/registration.hpp"
#include "twinslam/registration/twin_index.hpp"
#include "twinslam/sim/feature_tracks.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/surface_distance.hpp"
#include "twinslam/trajectory/io.hpp"
#include "twinslam/twin/store.hpp"

namespace {

using namespace twinslam;
using namespace twinslam::registration;

struct Options {
  std::string dataset, store;
  double horizon_s = 2.0, noise_m = 0.0;
  bool without_details = false;
  RegistrationConfig config;
};

Options parse(int argc, char** argv) {
  if (argc < 3) throw UsageError("usage: bench_registration_floor DATASET TWIN_STORE [--horizon-s H] [--noise-m N] "
                                 "[--without-details] [--config REGISTRATION.yaml]");
  Options o{argv[1], argv[2]};
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--without-details") {
      o.without_details = true;
    } else if (a == "--config" && i + 1 < argc) {
      o.config = load_registration_config(argv[++i]);
      o.config.validate(argv[i]);
    } else if ((a == "--horizon-s" || a == "--noise-m") && i + 1 < argc) {
      (a == "--horizon-s" ? o.horizon_s : o.noise_m) = std::atof(argv[++i]);
    } else {
      throw UsageError("bench_registration_floor: unknown option '" + a + "'");
    }
  }
  return o;
}

// The dataset's scenario (echoed in dataset.yaml), so the world and its surface samples are the simulator's own.
sim::Scenario dataset_scenario(const std::string& dataset) {
  const std::string file = dataset + "/dataset.yaml";
  const YAML::Node y = YAML::LoadFile(file);
  if (!y["scenario"]) throw InputError(file + ": no scenario section (not a simulated dataset)");
  std::stringstream text;
  text << y["scenario"];
  return sim::parse_scenario_yaml(text.str(), file);
}

// Landmark ids of the ideal tracks per frame stamp.
std::map<std::int64_t, std::vector<std::size_t>> tracks(const std::string& dataset) {
  const std::string file = dataset + "/mav0/cam0/features.csv";
  std::map<std::int64_t, std::vector<std::size_t>> seen;
  read_csv(file, 6, [&](const CsvRow& row) {
    if (row.line == 1) return;  // header
    seen[parse_int64(file, row, 0, "timestamp")].push_back(static_cast<std::size_t>(parse_int64(file, row, 1, "id")));
  });
  if (seen.empty()) throw InputError(file + ": no feature tracks (simulate with --features)");
  return seen;
}

// Spearman's rank correlation (no ties expected in continuous values).
double rank_correlation(const std::vector<double>& x, const std::vector<double>& y) {
  const auto ranks = [](const std::vector<double>& v) {
    std::vector<std::size_t> order(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (std::size_t k = 0; k < order.size(); ++k) r[order[k]] = static_cast<double>(k);
    return r;
  };
  const std::vector<double> rx = ranks(x), ry = ranks(y);
  const double mean = 0.5 * static_cast<double>(x.size() - 1);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (rx[i] - mean) * (ry[i] - mean);
    sxx += (rx[i] - mean) * (rx[i] - mean);
    syy += (ry[i] - mean) * (ry[i] - mean);
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

int run(const Options& o) {
  const sim::Scenario scenario = dataset_scenario(o.dataset);
  const sim::City city = sim::build_city(scenario.city, scenario.seed);
  // The ideal tracks' landmarks are these samples, by index (tools/sim/pipeline/src/simulate.cpp).
  const auto samples = sim::sample_surface(city.mesh, sim::FeatureTrackConfig{}.landmarks, scenario.seed);
  const auto seen = tracks(o.dataset);
  const Trajectory gt = read_dataset_groundtruth(o.dataset);
  const twin::TwinIndex store = twin::read_twin_index(o.store);
  TwinTileIndex index(store.tile_size_m);
  for (const auto& t : store.tiles) add_tile_from_store(index, o.store, store, t.key);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, o.noise_m);
  std::vector<double> error_m, error_deg, sigma_m;
  double nees = 0.0, rank = 0.0;
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();  // sum of the position errors: a twin that lacks details biases
  int keyframes = 0;
  const std::int64_t first = seen.begin()->first;
  for (std::int64_t t = first + 10'000'000'000LL; t <= seen.rbegin()->first; t += 1'000'000'000LL) {
    const auto frame = seen.lower_bound(t);
    const auto pose = std::lower_bound(gt.poses.begin(), gt.poses.end(), frame->first,
                                       [](const StampedPose& p, std::int64_t s) { return p.stamp_ns < s; });
    if (pose == gt.poses.end()) break;
    std::set<std::size_t> ids;
    const auto horizon_ns = static_cast<std::int64_t>(o.horizon_s * 1e9);
    for (auto f = seen.lower_bound(frame->first - horizon_ns); f != seen.end() && f->first <= frame->first; ++f) {
      ids.insert(f->second.begin(), f->second.end());
    }
    SourceInput in;  // T_WL = identity: L is W, and the keyframe is at its true pose
    in.T_LB = pose->T_XB;
    for (const std::size_t id : ids) {
      if (id >= samples.size()) continue;  // a point on a moving car (ids after the static ones): not the twin's
      if (o.without_details && city.mesh.kind[samples[id].triangle] == sim::SurfaceKind::kDetail) continue;
      in.landmarks.push_back({samples[id].p_W + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)), 1.0});
    }
    ++keyframes;
    const RegistrationResult r = register_cloud(o.config, index, in, std::nullopt);
    if (!r.accepted()) continue;
    nees += r.correction_xi.dot(r.information * r.correction_xi);
    rank += static_cast<double>(6 - r.details.zero_directions);
    sigma_m.push_back(geometry::observed_position_sigma_m(r.information));
    error_m.push_back(r.correction_xi.tail<3>().norm());
    bias += r.correction_xi.tail<3>();
    error_deg.push_back(r.correction_xi.head<3>().norm() * 180.0 / M_PI);
  }
  if (error_m.empty()) throw InputError(o.dataset + ": no registration was accepted");
  const auto over = std::count_if(error_m.begin(), error_m.end(), [](double e) { return e > 0.5; });
  std::printf("keyframes %d, accepted %zu; position error median %.3f m, p90 %.3f m, max %.3f m, > 0.5 m: %ld; "
              "rotation error median %.3f deg, max %.3f deg\n",
              keyframes, error_m.size(), quantile(error_m, 0.5), quantile(error_m, 0.9), quantile(error_m, 1.0),
              static_cast<long>(over), quantile(error_deg, 0.5), quantile(error_deg, 1.0));
  const auto n = static_cast<double>(error_m.size());
  std::printf("mean position error (bias) in W: %.3f %.3f %.3f m\n", bias.x() / n, bias.y() / n, bias.z() / n);
  std::printf("information: mean xi^T W xi %.2f (consistent: its mean rank %.2f); predicted position sigma median "
              "%.3f m, rank correlation with the error %.2f\n",
              nees / n, rank / n, quantile(sigma_m, 0.5), rank_correlation(sigma_m, error_m));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_registration_floor: %s\n", e.what());
    return 2;
  }
}
