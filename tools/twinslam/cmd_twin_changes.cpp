// `twinslam twin changes RUN [--out DIR]` (CONTRACTS.md): where the world no longer matches the twin, from the
// landmarks a run placed in W (RUN/landmarks.csv) against its dataset's twin: DIR/twin_changes.geojson and
// DIR/twin_changes.png, one line per change found on stdout.
#include <cstdio>
#include <fstream>

#include "commands.hpp"
#include "dataset_twin.hpp"
#include "run_folder.hpp"
#include "twin_changes_report.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

namespace {

struct ChangesOptions {
  std::string run, out;
  twin::TwinChangeConfig config;
};

int run_changes(const ChangesOptions& o) {
  const auto found = write_twin_change_report(o.run, o.out.empty() ? o.run : o.out, o.config);
  for (const twin::TwinChange& c : found.places) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : c.footprint_W) centre += p;
    centre /= static_cast<double>(c.footprint_W.size());
    std::printf("  %-7s at E %.1f N %.1f m: %zu landmarks off the twin (mean %.2f m), %zu sight lines through it "
                "(mean depth %.2f m), seen %.1f-%.1f s\n",
                c.kind.c_str(), centre.x(), centre.y(), c.landmarks, c.mean_distance_m, c.sight_lines, c.mean_depth_m,
                c.first_s, c.last_s);
  }
  return kExitOk;
}

}  // namespace

twin::TwinChanges write_twin_change_report(const fs::path& run, const fs::path& out,
                                           const twin::TwinChangeConfig& config, bool print) {
  config.validate();
  const nlohmann::json j = read_run_json(run);
  const std::string dataset = j.value("dataset", "");
  if (dataset.empty() || !fs::exists(fs::path(dataset) / "dataset.yaml")) {
    throw InputError((run / "run.json").string() + ": its dataset '" + dataset +
                     "' (with dataset.yaml naming the twin) is not here: nothing to compare the landmarks with");
  }
  const twin::Mesh twin_W = load_dataset_twin(read_dataset_geo(dataset));
  const Trajectory flight_W = estimate_in_W(run, j);
  const std::int64_t start_ns = read_run_trajectory(run).poses.front().stamp_ns;  // times from the first estimate
  const auto sightings = read_sightings(run, start_ns, flight_W.poses.front().stamp_ns);
  twin::TwinChanges found = twin::find_twin_changes(twin_W, sightings, config);

  fs::create_directories(out);
  const twin::EnuFrame W(run_origin(run, j));
  const fs::path geojson = out / "twin_changes.geojson", png = out / "twin_changes.png";
  std::ofstream f(geojson);
  if (!(f << changes_geojson(found.places, W).dump(1) << '\n')) throw InputError(geojson.string() + ": cannot write");
  write_changes_png(png, twin_W, flight_W, found.places);
  if (print) std::printf("twin changes: %zu found from %zu landmarks in W (%zu used: %zu off the twin, %zu sight lines through "
              "it) -> %s, %s\n", found.places.size(), sightings.size(), found.landmarks_used, found.unexplained,
              found.sight_lines, geojson.string().c_str(), png.string().c_str());
  return found;
}

void add_twin_changes_command(CLI::App& twin, int& exit_code) {
  auto o = std::make_shared<ChangesOptions>();
  CLI::App* cmd = twin.add_subcommand("changes", "Where a run's landmarks disagree with its dataset's twin: "
                                                 "twin_changes.geojson and twin_changes.png");
  cmd->add_option("RUN", o->run, "Run folder of a run aligned to W (twin or GNSS modes)")->required();
  cmd->add_option("--out", o->out, "Folder for the files (default: RUN)");
  cmd->add_option("--min-distance", o->config.min_distance_m, "A landmark this far from the twin is unexplained [m]")
      ->capture_default_str();
  cmd->add_option("--min-evidence", o->config.min_evidence, "Evidence a place needs to be reported")
      ->capture_default_str();
  cmd->add_option("--min-quality", o->config.min_quality, "Landmarks of lower quality (0..1) are not used")
      ->capture_default_str();
  cmd->add_option("--min-span", o->config.min_span_s, "... seen over at least this long [s]")->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = run_changes(*o); });
}

}  // namespace twinslam::cli
