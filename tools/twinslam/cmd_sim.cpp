// `twinslam sim --scenario NAME|FILE.yaml --out DIR [--seed N] [--duration S] [--features] [--preview]`:
// simulate a city flight into a dataset folder that `twinslam run` and `ingest` replay like a real EuRoC sequence.
#include <cstdio>

#include "commands.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/simulate.hpp"

namespace twinslam::cli {

void add_sim_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("sim", "Simulate a scenario into a dataset (EuRoC layout + twin + ground truth)");
  struct Options {
    std::string scenario = "city-loops", out;
    std::optional<std::uint64_t> seed;
    std::optional<double> duration;
    sim::SimOptions sim;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("--scenario", o->scenario,
                  "Built-in (tiny, city-loops, city-survey, city-long) or a scenario YAML file")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Dataset folder to write")->required();
  cmd->add_option("--seed", o->seed, "Override the scenario's seed");
  cmd->add_option("--duration", o->duration, "Override trajectory.duration_s [s]");
  cmd->add_flag("--features", o->sim.features, "Also write ideal feature tracks (mav0/cam0/features.csv)");
  cmd->add_option("--feature-noise", o->sim.feature_config.pixel_sigma, "Pixel noise of the ideal tracks [px]")
      ->capture_default_str();
  cmd->add_flag("--preview", o->sim.preview, "Write preview/top_down.png and a few frames");
  cmd->add_flag("--no-images{false}", o->sim.images,
                "Render no images (cam0/data.csv lists none): with --features, a features-only dataset in seconds");
  cmd->add_flag("--quiet", o->quiet, "No progress bar");
  cmd->callback([o, &exit_code] {
    sim::Scenario scenario = sim::load_scenario(o->scenario);
    if (o->seed) scenario.seed = *o->seed;
    if (o->duration) scenario.trajectory.duration_s = *o->duration;
    sim::validate_scenario(scenario, o->scenario);
    o->sim.out = o->out;
    o->sim.progress = !o->quiet;
    const auto s = sim::simulate(scenario, o->sim);
    std::printf("sim %s: scenario %s, seed %llu: %.1f s, %.1f m, %zu frames, %zu IMU, %zu GNSS%s in %.1f s\n",
                o->out.c_str(), scenario.name.c_str(), static_cast<unsigned long long>(scenario.seed), s.duration_s,
                s.path_length_m, s.frames, s.imu, s.gnss,
                o->sim.features ? (", " + std::to_string(s.feature_rows) + " feature observations").c_str() : "",
                s.wall_s);
    std::printf("world %zu triangles, twin %zu triangles (twin/twin.ply)\n", s.world_triangles, s.twin_triangles);
    exit_code = kExitOk;
  });
}

}  // namespace twinslam::cli
