// `twinslam eval`: accuracy of an estimate against the ground truth (CONTRACTS.md, "twinslam eval --json").
#include <iostream>
#include <memory>
#include <string>

#include "bench_world.hpp"
#include "commands.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/eval/evaluate.hpp"
#include "twinslam/eval/plots.hpp"
#include "twinslam/eval/report.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::cli {
namespace {

struct EvalOptions {
  std::string gt, est, align = "none", plots;
  std::size_t align_first = 0;
  double max_dt_ms = 20.0;
  bool json = false;
};

int run_eval(const EvalOptions& o) {
  eval::EvalConfig config;
  config.align = eval::parse_align_mode(o.align);
  config.align_first = o.align_first;
  if (!(o.max_dt_ms > 0.0)) throw UsageError("--max-dt-ms must be positive");
  config.max_dt_ns = static_cast<std::int64_t>(o.max_dt_ms * 1e6);
  const Trajectory gt = read_trajectory_any(o.gt);
  Trajectory est = read_trajectory_any(o.est);
  // A run of a world-frame mode is in L until its alignment is declared (run.json aligned_from_stamp_ns): without an
  // alignment of the estimate, only the poses from then on are in W and comparable with the truth, as in `bench`.
  std::optional<WorldStart> start;
  const std::filesystem::path run_json = std::filesystem::path(o.est) / "run.json";
  if (config.align == eval::AlignMode::None && std::filesystem::is_regular_file(run_json)) {
    try {
      start = read_world_start(o.est, gt, est);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(run_json.string() + ": not a run.json: " + e.what());
    }
    if (start) keep_world_poses(est, *start);
  }
  const eval::EvalResult result = eval::evaluate(gt, est, config);

  std::vector<std::filesystem::path> pngs;
  if (!o.plots.empty()) pngs = eval::write_eval_plots(o.plots, gt, {{"estimate", &result}});
  if (o.json) {
    nlohmann::json j = eval::to_json(result);
    j["gt_file"] = gt.source;
    j["est_file"] = est.source;
    if (start) j["evaluated_from_stamp_ns"] = start->aligned_from_stamp_ns;
    if (start && !start->out_of_world_ns.empty()) j["excluded_out_of_world_ns"] = start->out_of_world_ns;
    std::cout << j.dump() << std::endl;  // exactly one object, one line: scripts parse stdout
  } else {
    std::cout << "ground truth " << gt.source << " (" << gt.size() << " poses)\n"
              << "estimate     " << est.source << " (" << est.size() << " poses)\n";
    if (start) {
      std::cout << "evaluated from the run's alignment to W on, " << start->aligned_after_s
                << " s after its first estimate (run.json aligned_from_stamp_ns; before that it is in L)\n";
      for (const auto& [first, last] : start->out_of_world_ns) {
        std::cout << "not evaluated: poses " << first << "-" << last
                  << " ns, not in W (run.json out_of_world_ns: the estimator had restarted or re-initialized)\n";
      }
    }
    std::cout << eval::format_table(result);
    for (const auto& png : pngs) std::cout << "plot " << png.string() << '\n';
  }
  return 0;
}

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "Accuracy of an estimate against ground truth: ATE and RPE (Zhang & Scaramuzza, IROS 2018)");
  cmd->add_option("--gt", opts->gt,
                  "Ground truth: dataset folder (groundtruth.tum or EuRoC mav0/state_groundtruth_estimate0/data.csv), "
                  "EuRoC .csv or TUM file")
      ->type_name("DIR|FILE")
      ->required();
  cmd->add_option("--est", opts->est, "Estimate: run folder (its trajectory.tum) or TUM file")
      ->type_name("RUN|FILE")
      ->required();
  cmd->add_option("--align", opts->align,
                  "Alignment before ATE: none (estimate already in W), posyaw (4-DoF, VIO), se3, sim3 (monocular)")
      ->type_name("MODE")
      ->capture_default_str();
  cmd->add_option("--align-first", opts->align_first, "Align on the first N associated poses only (0 = all)")
      ->type_name("N")
      ->capture_default_str();
  cmd->add_option("--max-dt-ms", opts->max_dt_ms, "Association window: largest |dt| between paired stamps [ms]")
      ->type_name("MS")
      ->capture_default_str();
  cmd->add_flag("--json", opts->json, "Print one JSON object on stdout instead of the table");
  cmd->add_option("--plots", opts->plots, "Write PNG plots (trajectory views, errors over time, RPE) into DIR")
      ->type_name("DIR");
  cmd->callback([opts, &exit_code] { exit_code = run_eval(*opts); });
}

}  // namespace twinslam::cli
