// bench_gnss_learned [--scenario NAME|FILE] [--seeds N] [--out DIR]: `gnss.model: raytrace` against `gnss.model:
// learned` along the scenario's flight (its city and flight built once from the scenario's seed), for the scenario's
// seed and N - 1 further seeds of the GNSS models (101, 102, ...; the learned model is trained anew for each, as
// `twinslam sim` would). Prints per seed and band the horizontal error mean and 95th percentile of both (and the
// vertical median), then the averages, how many same-seed pairs agree within 25 % on both numbers, and - as the
// criterion's noise floor - how many ray-traced runs of other seeds agree with the scenario seed's ray-traced run.
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

std::vector<gnss::BandStats> bands(const RaytraceGnss& g) {
  std::vector<gnss::HeightSample> s;
  for (const GnssSample& f : g.fixes) s.push_back({f.true_p_W.z(), f.bias_W.head<2>().norm(), std::abs(f.bias_W.z())});
  return gnss::errors_by_height(s);
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
  std::printf("%-5s %-6s %28s %28s\n", "seed", "band", "raytrace mean / p95 / v med", "learned mean / p95 / v med");
  for (int k = 0; k < seeds; ++k) {
    const std::uint64_t seed = k == 0 ? s.seed : 100 + static_cast<std::uint64_t>(k);
    rt.push_back(bands(simulate_gnss_raytrace(stamps, p_W, s.origin, world, seed)));
    learned.push_back(bands(run_learned_gnss(out, stamps, p_W, city.hints, s.origin, world, seed)));
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
  return 0;
}
