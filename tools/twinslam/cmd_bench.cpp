// `twinslam bench DIR --out BENCH [--modes MODE,...]`: runs the pipeline once per mode on one dataset and compares
// the modes like the paper's Table I: ATE_p [m], ATE_R [deg], per-frame time, registration time.
// Modes with a world frame are evaluated without alignment; `vio` (local frame only) with posyaw (4-DoF).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench_registrations.hpp"
#include "bench_world.hpp"
#include "commands.hpp"
#include "modes.hpp"
#include "run_pipeline.hpp"
#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/eval/evaluate.hpp"
#include "twinslam/eval/plots.hpp"
#include "twinslam/eval/report.hpp"
#include "twinslam/eval/stats.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

namespace {
// Median of one column of a CSV with a header row; nullopt when there are no rows.
std::optional<double> column_median(const fs::path& file, std::size_t columns, std::size_t col,
                                    const std::function<bool(const CsvRow&)>& keep = {}) {
  if (!fs::exists(file)) return std::nullopt;
  std::vector<double> values;
  read_csv(file, columns, [&](const CsvRow& row) {
    if (row.line == 1) return;  // header
    if (keep && !keep(row)) return;
    values.push_back(parse_double(file, row, col, "value"));
  });
  if (values.empty()) return std::nullopt;
  return eval::quantile(values, 0.5);
}

std::string cell(const std::optional<double>& v, const char* fmt) {
  if (!v) return "-";
  char buf[32];
  std::snprintf(buf, sizeof(buf), fmt, *v);
  return buf;
}
}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("bench", "Run and evaluate every mode on a dataset; write BENCH/table.md");
  struct Options {
    std::string dataset, out;
    std::vector<std::string> modes = all_modes();
    bool features = false, no_progress = false;
    std::string config_dir, weights = "adaptive", initial_pose;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("dataset", o->dataset, "Dataset folder with ground truth")->required();
  cmd->add_option("--out", o->out, "Output folder BENCH")->required();
  cmd->add_option("--modes", o->modes, "Modes to compare")
      ->delimiter(',')
      ->check(CLI::IsMember(all_modes()));
  cmd->add_flag("--features", o->features, "Feed the dataset's ideal feature tracks instead of images");
  cmd->add_option("--config-dir", o->config_dir, "Folder of <service>.yaml configs, passed to every run");
  cmd->add_option("--weights", o->weights, "Twin modes: registration information weighting")
      ->check(CLI::IsMember({"paper", "adaptive", "fixed"}))
      ->capture_default_str();
  cmd->add_option("--initial-pose", o->initial_pose, "Twin modes without GNSS: \"E N U YAW_DEG\" (see run)");
  cmd->add_flag("--no-progress", o->no_progress, "No progress bar per mode on stderr");
  cmd->callback([o, &exit_code] {
    const Trajectory gt = read_dataset_groundtruth(o->dataset);
    fs::create_directories(o->out);
    std::vector<std::string> done;
    std::vector<eval::EvalResult> results;
    std::map<std::string, std::pair<std::optional<double>, std::optional<double>>> times;
    std::map<std::string, double> aligned_after;  // world-frame modes: seconds from the first estimate to W
    std::map<std::string, WorldStart> starts;     // world-frame modes
    std::map<std::string, RegistrationTruth> registration_truth;  // twin modes with accepted registrations in W
    nlohmann::json metrics = nlohmann::json::object();
    int code = kExitOk;
    // Modes whose fusion exists today run; the others are refused with the reason and listed in the table's note.
    std::vector<std::string> unavailable;
    std::vector<std::string> not_run;  // implemented, but this dataset lacks what the mode needs
    for (const auto& mode : o->modes) {
      if (!mode_implemented(mode)) {
        try {
          require_implemented_mode(mode);
        } catch (const UsageError& e) {
          std::cerr << "bench: " << e.what() << std::endl;
        }
        unavailable.push_back(mode);
        continue;
      }
      RunOptions run;
      run.dataset = o->dataset;
      run.mode = mode;
      run.out = (fs::path(o->out) / "runs" / mode).string();
      run.features = o->features;
      run.config_dir = o->config_dir;
      run.weights = o->weights;
      run.initial_pose = o->initial_pose;
      run.quiet = true;
      run.progress = !o->no_progress;
      run.progress_label = mode;
      std::cerr << "bench: running " << mode << " ..." << std::endl;
      int run_code = kExitOk;
      try {
        run_code = run_pipeline(run);
      } catch (const std::exception& e) {
        // What this dataset lacks for the mode (no GNSS, no origin or twin): noted in the table, the others still run.
        if (dynamic_cast<const UsageError*>(&e) == nullptr && dynamic_cast<const InputError*>(&e) == nullptr) throw;
        std::cerr << "bench: " << mode << " not run: " << e.what() << std::endl;
        not_run.push_back(mode + " (" + e.what() + ")");
        continue;
      }
      if (run_code != kExitOk || !fs::exists(fs::path(run.out) / "trajectory.tum")) {
        std::cerr << "bench: " << mode << " produced no trajectory (see " << run.out << "/logs)" << std::endl;
        code = kExitInternal;
        continue;
      }
      eval::EvalConfig cfg;
      cfg.align = mode == "vio" ? eval::AlignMode::PosYaw : eval::AlignMode::None;
      Trajectory est = read_run_trajectory(run.out);
      if (mode != "vio") {
        // World-frame modes: evaluated in W without any alignment, from the pose where T_WB entered W on (before
        // that the estimate is in L). A mode that never aligned is reported as such, not evaluated in L.
        const auto start = read_world_start(run.out, gt, est);
        if (!start) {
          std::cerr << "bench: " << mode << " never aligned to W (see " << run.out << "/logs)" << std::endl;
          code = kExitInternal;
          continue;
        }
        keep_world_poses(est, *start);
        aligned_after[mode] = start->aligned_after_s;
        starts[mode] = *start;
      }
      results.push_back(eval::evaluate(gt, est, cfg));
      done.push_back(mode);
      const fs::path timing = fs::path(run.out) / "timing.csv";
      const auto tracking = column_median(timing, 4, 1), estimator = column_median(timing, 4, 2);
      std::optional<double> frame_ms;
      if (tracking && estimator) frame_ms = *tracking + *estimator;
      times[mode] = {frame_ms, column_median(fs::path(run.out) / "registrations.csv", 29, 5)};
      metrics[mode] = eval::to_json(results.back());
      if (const auto truth = evaluate_registrations(run.out, gt)) {
        registration_truth[mode] = *truth;
        metrics[mode]["registrations_vs_truth"] = {
            {"accepted", truth->accepted},           {"off", truth->off},
            {"threshold_m", truth->threshold_m},     {"median_before_m", truth->median_before_m},
            {"median_after_m", truth->median_after_m}, {"max_after_m", truth->max_after_m},
            {"median_after_deg", truth->median_after_deg}, {"max_after_deg", truth->max_after_deg}};
      }
    }
    // The table in the shape of the paper's Table I: metrics as rows, systems (modes) as columns.
    std::ostringstream table;
    table << "| Metric |";
    for (const auto& m : done) table << ' ' << m << (m == "vio" ? " (posyaw)" : " (none)") << " |";
    table << "\n|---|";
    for (std::size_t i = 0; i < done.size(); ++i) table << "---|";
    table << "\n| ATE_p [m] |";
    for (const auto& r : results) table << ' ' << cell(r.ate.pos.rmse, "%.3f") << " |";
    table << "\n| ATE_R [deg] |";
    for (const auto& r : results) table << ' ' << cell(r.ate.rot.rmse, "%.3f") << " |";
    table << "\n| ATE_p [% of path] |";
    for (const auto& r : results) {
      table << ' ' << cell(100.0 * r.ate.pos.rmse / std::max(r.length_m, 1e-9), "%.3f") << " |";
    }
    // One row per metric, one cell per mode; "-" where a mode has no such value.
    const auto row = [&](const char* name, const std::function<std::string(const std::string&)>& value) {
      table << "\n| " << name << " |";
      for (const auto& m : done) table << ' ' << value(m) << " |";
    };
    const auto start_of = [&](const std::string& m) { return starts.count(m) ? &starts.at(m) : nullptr; };
    const auto truth_of = [&](const std::string& m) {
      return registration_truth.count(m) ? &registration_truth.at(m) : nullptr;
    };
    row("error in W 10 s after start [m / deg]", [&](const std::string& m) {
      const WorldStart* w = start_of(m);
      return w ? cell(w->error_at_10s_m, "%.3f") + " / " + cell(w->error_at_10s_deg, "%.3f") : std::string("-");
    });
    row("per-frame time, median [ms]", [&](const std::string& m) { return cell(times[m].first, "%.2f"); });
    row("registration time, median [ms]", [&](const std::string& m) { return cell(times[m].second, "%.2f"); });
    row("LocalMap -> Registration, median / p99 [ms]", [&](const std::string& m) {
      const WorldStart* w = start_of(m);
      return w && w->latency_median_ms ? cell(w->latency_median_ms, "%.1f") + " / " + cell(w->latency_p99_ms, "%.1f")
                                       : std::string("-");
    });
    row("accepted registrations > 0.5 m from the truth / all", [&](const std::string& m) {
      const RegistrationTruth* t = truth_of(m);
      return t ? std::to_string(t->off) + " / " + std::to_string(t->accepted) : std::string("-");
    });
    row("registration position error, median before / after, max after [m]", [&](const std::string& m) {
      const RegistrationTruth* t = truth_of(m);
      return t ? cell(t->median_before_m, "%.3f") + " / " + cell(t->median_after_m, "%.3f") + " / " +
                     cell(t->max_after_m, "%.3f")
               : std::string("-");
    });
    table << "\n\nPath length " << cell(results.empty() ? std::nullopt : std::optional<double>(results[0].length_m), "%.1f")
          << " m. ATE alignment in parentheses: posyaw for the local-frame VIO, none for modes with a world frame";
    if (!aligned_after.empty()) {
      table << " (evaluated from their alignment to W on:";
      for (const auto& [m, s] : aligned_after) table << ' ' << m << ' ' << cell(s, "%.1f") << " s";
      table << " after the first estimate)";
    }
    table << ".\n";
    if (!unavailable.empty()) {
      table << "Not available yet:";
      for (const auto& m : unavailable) table << ' ' << m;
      table << ".\n";
    }
    if (!not_run.empty()) {
      table << "Not run on this dataset:";
      for (std::size_t i = 0; i < not_run.size(); ++i) table << (i ? "; " : " ") << not_run[i];
      table << ".\n";
    }
    if (done.empty() && code == kExitOk) code = kExitBadInput;  // nothing could run: wrong dataset or modes
    std::ofstream(fs::path(o->out) / "table.md") << table.str();
    std::ofstream(fs::path(o->out) / "metrics.json") << metrics.dump(2) << '\n';
    std::vector<eval::PlotRun> plot_runs;
    for (std::size_t i = 0; i < done.size(); ++i) plot_runs.push_back({done[i], &results[i]});
    if (!plot_runs.empty()) eval::write_eval_plots(o->out, gt, plot_runs);
    std::cout << table.str();
    exit_code = code;
  });
}

}  // namespace twinslam::cli
