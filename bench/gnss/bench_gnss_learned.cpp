// bench_gnss_learned [--scenario NAME|FILE] [--seeds N] [--first-seed S] [--positions P] [--out DIR]:
// `gnss.model: raytrace` against `gnss.model: learned` along the scenario's flight (its city and flight built once from
// the scenario's seed), for the scenario's seed and N - 1 further seeds of the GNSS models (S, S + 1, ...; S = 101;
// the learned model is trained anew for each, as `twinslam sim` would, on P positions, default 1500). Prints per seed
// and band the horizontal error mean and 95th percentile of both (and the vertical median), then the averages, how
// many same-seed pairs agree within 25 % on both numbers, and - as the criterion's noise floor - how many ray-traced
// runs of other seeds agree with the scenario seed's ray-traced run; last the statistics of all draws' fixes pooled
// per band.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "twinslam/gnss/height_bands.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/gnss_learned.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/city.hpp"

namespace {

using namespace twinslam;
using namespace twinslam::sim;

std::vector<gnss::HeightSample> samples(const RaytraceGnss& g) {
  std::vector<gnss::HeightSample> s;
  for (const GnssSample& f : g.fixes) s.push_back({f.true_p_W.z(), f.bias_W.head<2>().norm(), std::abs(f.bias_W.z())});
  return s;
}

bool within(const gnss::BandStats& a, const gnss::BandStats& ref, double tol) {
  return std::abs(a.h_mean_m / ref.h_mean_m - 1) <= tol && std::abs(a.h_p95_m / ref.h_p95_m - 1) <= tol;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Learned against ray-traced GNSS by height band over several seeds");
  std::string name = "city-loops", out = "/tmp/bench_gnss_learned";
  int seeds = 10;
  app.add_option("--scenario", name, "Built-in scenario or YAML file");
  app.add_option("--seeds", seeds, "Seeds of the GNSS models (the scenario's first)")->check(CLI::Range(1, 1000));
  std::uint64_t first_seed = 101;
  app.add_option("--first-seed", first_seed, "Seed of the second draw; the others follow it");
  GnssTrainingConfig training;
  app.add_option("--positions", training.positions, "Training positions per draw (GnssTrainingConfig)")
      ->check(CLI::Range(100, 100000));
  app.add_option("--out", out, "Folder for the learned model's files (overwritten per seed)");
  CLI11_PARSE(app, argc, argv);
  const Scenario s = load_scenario(name);
  const City city = build_city(s.city, s.seed);
  const FlightTrajectory flight = make_flight_trajectory(s, city.hints);
  const std::vector<std::int64_t> stamps = sample_stamps(s.gnss.rate_hz, flight.duration());
  std::vector<Eigen::Vector3d> p_W;
  for (const std::int64_t t : stamps) p_W.push_back(flight.at(time_s(t)).p_W);
  const EmbreeScene world(city.mesh);
  std::vector<std::vector<gnss::BandStats>> rt, learned;
  std::vector<gnss::HeightSample> rt_pooled, learned_pooled;  // every draw's fixes together
  std::printf("%-5s %-6s %28s %28s\n", "seed", "band", "raytrace mean / p95 / v med", "learned mean / p95 / v med");
  for (int k = 0; k < seeds; ++k) {
    const std::uint64_t seed = k == 0 ? s.seed : first_seed + static_cast<std::uint64_t>(k - 1);
    const auto rt_fixes = samples(simulate_gnss_raytrace(stamps, p_W, s.origin, world, seed));
    const auto learned_fixes = samples(run_learned_gnss(out, stamps, p_W, city.hints, s.origin, world, seed, training));
    rt.push_back(gnss::errors_by_height(rt_fixes));
    learned.push_back(gnss::errors_by_height(learned_fixes));
    rt_pooled.insert(rt_pooled.end(), rt_fixes.begin(), rt_fixes.end());
    learned_pooled.insert(learned_pooled.end(), learned_fixes.begin(), learned_fixes.end());
    for (std::size_t b = 0; b < rt.back().size(); ++b) {
      if (rt.back()[b].fixes == 0) continue;
      const auto& r = rt.back()[b];
      const auto& l = learned.back()[b];
      std::printf("%-5llu %-6s %10.2f %8.2f %8.2f %10.2f %8.2f %8.2f%s\n", static_cast<unsigned long long>(seed),
                  r.name.c_str(), r.h_mean_m, r.h_p95_m, r.v_median_m, l.h_mean_m, l.h_p95_m, l.v_median_m,
                  within(l, r, 0.25) ? "" : "   (not within 25 %)");
    }
  }
  std::printf("\n%-6s %22s %22s %14s %18s\n", "band", "raytrace avg mean/p95", "learned avg mean/p95",
              "pairs in 25 %", "rt vs rt seed 1st");
  for (std::size_t b = 0; b < rt[0].size(); ++b) {
    if (rt[0][b].fixes == 0) continue;
    double rm = 0, rp = 0, lm = 0, lp = 0;
    int pairs = 0, self = 0;
    for (int k = 0; k < seeds; ++k) {
      rm += rt[k][b].h_mean_m / seeds;
      rp += rt[k][b].h_p95_m / seeds;
      lm += learned[k][b].h_mean_m / seeds;
      lp += learned[k][b].h_p95_m / seeds;
      pairs += within(learned[k][b], rt[k][b], 0.25) ? 1 : 0;
      if (k > 0) self += within(rt[k][b], rt[0][b], 0.25) ? 1 : 0;
    }
    std::printf("%-6s %12.2f %8.2f %13.2f %8.2f %10d/%-3d %13d/%d\n", rt[0][b].name.c_str(), rm, rp, lm, lp, pairs,
                seeds, self, seeds - 1);
  }
  // The draws pooled: each band's mean and 95th percentile over all draws' fixes at once. A band of one flight is one
  // stretch of correlated errors, so one draw's statistics scatter widely and their average is held by the worst
  // draws; the pooled distribution is what the model generates there.
  const auto rp = gnss::errors_by_height(rt_pooled), lp = gnss::errors_by_height(learned_pooled);
  std::printf("\npooled  %22s %22s %14s\n", "raytrace mean / p95", "learned mean / p95", "learned / rt");
  for (std::size_t b = 0; b < rp.size(); ++b) {
    if (rp[b].fixes == 0 || lp[b].fixes == 0) continue;
    std::printf("%-6s %12.2f %8.2f %13.2f %8.2f %8.2f / %.2f%s\n", rp[b].name.c_str(), rp[b].h_mean_m, rp[b].h_p95_m,
                lp[b].h_mean_m, lp[b].h_p95_m, lp[b].h_mean_m / rp[b].h_mean_m, lp[b].h_p95_m / rp[b].h_p95_m,
                within(lp[b], rp[b], 0.25) ? "" : "   (not within 25 %)");
  }
  return 0;
}
