// bench_gnss_canyon [--heights LO,HI] [--street-width M] [--antenna-height M] [--seed N] [--mask DEG]: the same
// receiver on
//  (1) the real pseudoranges of the smartLoc Berlin Potsdamer Platz excerpt (high-rises, 35-100 m), and
//  (2) the simulator's ray-traced pseudoranges along every street of a procedural city with buildings of similar
//      heights, the antenna at car height,
// and the horizontal error statistics of both with their ratio (issue 13: within a factor of 2).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "twinslam/eval/stats.hpp"
#include "twinslam/gnss/fix_errors.hpp"
#include "twinslam/gnss/receiver.hpp"
#include "twinslam/gnss/smartloc.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/gnss_raytrace.hpp"
#include "twinslam/sim/world/city.hpp"

namespace {

using namespace twinslam;

struct Stats {
  std::size_t epochs = 0, fixes = 0;
  double median = 0, p95 = 0, rmse = 0, v_median = 0;
};

Stats real_stats(const std::string& dir) {
  const auto epochs = gnss::read_smartloc_pseudoranges(dir + "/Berlin_Potsdamer_Platz_Input_first90s.txt");
  const auto truth = gnss::read_smartloc_ground_truth(dir + "/Berlin_Potsdamer_Platz_GT_first90s.txt");
  const auto s = gnss::fix_error_stats(epochs.size(), gnss::fix_errors(gnss::solve_epochs(epochs, {}), truth));
  return {s.epochs, s.fixes, s.h_err_median_m, s.h_err_p95_m, s.h_err_rmse_m, s.v_err_median_m};
}

// Street-level positions along every street centreline of the grid, 1.6 m apart (8 m/s at 5 Hz).
std::vector<Eigen::Vector3d> street_positions(const sim::StreetGrid& g, double antenna_m) {
  std::vector<Eigen::Vector3d> p;
  for (const double e : g.east_m) {
    for (double n = g.north_m.front(); n <= g.north_m.back(); n += 1.6) p.emplace_back(e, n, antenna_m);
  }
  for (const double n : g.north_m) {
    for (double e = g.east_m.front(); e <= g.east_m.back(); e += 1.6) p.emplace_back(e, n, antenna_m);
  }
  return p;
}

Stats sim_stats(const sim::City& city, double antenna_m, std::uint64_t seed, const sim::RaytraceGnssModel& model) {
  const std::vector<Eigen::Vector3d> p_W = street_positions(city.hints.streets, antenna_m);
  std::vector<std::int64_t> stamps;
  for (std::size_t i = 0; i < p_W.size(); ++i) stamps.push_back(sim::stamp_ns(0.2 * static_cast<double>(i)));
  const sim::EmbreeScene world(city.mesh);
  const sim::Origin berlin{52.5094, 13.3762, 75.0};
  const sim::RaytraceGnss g = sim::simulate_gnss_raytrace(stamps, p_W, berlin, world, seed, model);
  std::size_t los = 0;
  for (const auto& r : g.pseudoranges) los += r.line_of_sight ? 1 : 0;
  std::printf("simulated signals: %.1f per epoch, %.1f %% line of sight (with or without multipath), %.1f %% NLOS\n",
              static_cast<double>(g.pseudoranges.size()) / static_cast<double>(g.epochs),
              100.0 * static_cast<double>(los) / static_cast<double>(g.pseudoranges.size()),
              100.0 * static_cast<double>(g.pseudoranges.size() - los) / static_cast<double>(g.pseudoranges.size()));
  std::vector<double> h, v;
  for (const auto& f : g.fixes) {
    h.push_back(f.bias_W.head<2>().norm());
    v.push_back(std::abs(f.bias_W.z()));
  }
  return {g.epochs, g.fixes.size(), eval::quantile(h, 0.5), eval::quantile(h, 0.95), eval::compute_stats(h).rmse,
          eval::quantile(v, 0.5)};
}

void row(const char* name, const Stats& s) {
  std::printf("%-34s %7zu %7zu %9.2f %9.2f %9.2f %9.2f\n", name, s.epochs, s.fixes, s.median, s.p95, s.rmse,
              s.v_median);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ray-traced urban GNSS vs the real smartLoc excerpt"};
  std::vector<double> heights{35, 100};
  double street_width = 30, antenna = 1.5;
  std::uint64_t seed = 7;
  std::string smartloc = std::string(TWINSLAM_SHARED_DIR) + "/data/gnss/smartloc-berlin-potsdamer-platz-90s";
  app.add_option("--heights", heights, "Building height range of the simulated canyon [m]")->expected(2)->delimiter(',');
  app.add_option("--street-width", street_width, "Kerb to kerb [m]");
  app.add_option("--antenna-height", antenna, "Above ground [m]");
  app.add_option("--seed", seed, "City and noise seed");
  sim::RaytraceGnssModel model;
  app.add_option("--mask", model.elevation_mask_deg, "Elevation mask of the simulated receiver [deg]");
  app.add_option("--correlator", model.correlator_half_spacing_m, "Half the early-late spacing [m]");
  app.add_option("--smartloc", smartloc, "Folder of the smartLoc excerpt");
  CLI11_PARSE(app, argc, argv);

  sim::CityConfig cc;
  cc.size_m = 600;
  cc.height_m = {heights[0], heights[1]};
  sim::CityLayout layout;
  layout.street_width_m = street_width;
  layout.block_size_m = 80;
  const sim::City city = sim::build_city(cc, seed, layout);
  std::printf("%-34s %7s %7s %9s %9s %9s %9s\n", "horizontal error [m]", "epochs", "fixes", "median", "p95", "rmse",
              "v median");
  const Stats real = real_stats(smartloc);
  row("smartLoc Berlin Potsdamer Platz", real);
  const Stats sim = sim_stats(city, antenna, seed, model);
  char name[64];
  std::snprintf(name, sizeof name, "ray-traced canyon %.0f-%.0f m, %.0f m", heights[0], heights[1], street_width);
  row(name, sim);
  std::printf("ratio simulated / real: median %.2f, p95 %.2f\n", sim.median / real.median, sim.p95 / real.p95);
  return 0;
}
