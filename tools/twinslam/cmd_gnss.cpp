// `twinslam gnss solve INPUT --gt GT [--out FIXES.csv] [--json] [--config FILE.yaml]`: the receiver of
// twinslam_gnss (weighted least squares with fault exclusion, one clock per satellite system) on real pseudoranges in
// the smartLoc text format, and its horizontal/vertical error against the ground truth (ENU at the true position).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "gnss_commands.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/gnss/fix_errors.hpp"
#include "twinslam/gnss/frames.hpp"
#include "twinslam/gnss/receiver.hpp"
#include "twinslam/gnss/smartloc.hpp"

namespace twinslam::cli {
namespace {

using namespace twinslam::gnss;

struct GnssSolveOptions {
  std::string input, gt, out, config;
  bool json = false;
};

void write_fixes(const std::string& path, const std::vector<Fix>& fixes, const std::vector<FixError>& errors) {
  std::ofstream out(path);
  if (!out) throw InputError(where(path, 0, "cannot open for writing"));
  out << "#t [s],x_ecef [m],y_ecef [m],z_ecef [m],latitude [deg],longitude [deg],height [m],std_east [m],"
         "std_north [m],std_up [m],satellites_used,satellites_excluded,residual_test_passed,h_err [m],v_err [m]\n";
  std::size_t e = 0;
  for (const Fix& f : fixes) {
    if (!f.valid) continue;
    const Geodetic g = ecef_to_geodetic(f.p_ecef);
    const Eigen::Matrix3d R = rotation_enu_from_ecef(g.latitude_deg, g.longitude_deg);
    const Eigen::Vector3d sd = (R * f.cov_ecef * R.transpose()).diagonal().cwiseSqrt();
    while (e < errors.size() && errors[e].t_s < f.t_s) ++e;
    const bool has_err = e < errors.size() && errors[e].t_s == f.t_s;
    char line[512];
    std::snprintf(line, sizeof line, "%.3f,%.3f,%.3f,%.3f,%.9f,%.9f,%.3f,%.3f,%.3f,%.3f,%d,%zu,%d,", f.t_s,
                  f.p_ecef.x(), f.p_ecef.y(), f.p_ecef.z(), g.latitude_deg, g.longitude_deg, g.height_m, sd.x(),
                  sd.y(), sd.z(), f.satellites_used, f.excluded.size(), f.residual_test_passed ? 1 : 0);
    out << line;
    if (has_err) {
      std::snprintf(line, sizeof line, "%.3f,%.3f", errors[e].horizontal_m, errors[e].vertical_m);
      out << line;
    } else {
      out << ",";  // no truth point near this fix
    }
    out << "\n";
  }
  if (!out) throw InputError(where(path, 0, "write failed"));
}

void print_text(const FixErrorStats& s, const std::vector<Fix>& fixes) {
  std::map<std::string, int> no_fix;
  std::size_t excluded = 0;
  for (const Fix& f : fixes) {
    if (!f.valid) ++no_fix[f.reason];
    excluded += f.excluded.size();
  }
  std::printf("epochs %zu, fixes with truth %zu, satellites excluded %zu\n", s.epochs, s.fixes, excluded);
  for (const auto& [reason, n] : no_fix) std::printf("no fix (%d epochs): %s\n", n, reason.c_str());
  std::printf("horizontal error: median %.2f m, p95 %.2f m, rmse %.2f m; vertical error: median %.2f m\n",
              s.h_err_median_m, s.h_err_p95_m, s.h_err_rmse_m, s.v_err_median_m);
}

int run_gnss_solve(const GnssSolveOptions& o) {
  const ReceiverConfig config = o.config.empty() ? ReceiverConfig{} : load_receiver_config(o.config);
  const std::vector<Epoch> epochs = read_smartloc_pseudoranges(o.input);
  const std::vector<TruthPoint> truth = read_smartloc_ground_truth(o.gt);
  const std::vector<Fix> fixes = solve_epochs(epochs, config);
  const std::vector<FixError> errors = fix_errors(fixes, truth);
  const FixErrorStats s = fix_error_stats(epochs.size(), errors);
  if (!o.out.empty()) write_fixes(o.out, fixes, errors);
  if (o.json) {
    const nlohmann::json j = {{"epochs", s.epochs},
                              {"fixes", s.fixes},
                              {"h_err_median_m", s.h_err_median_m},
                              {"h_err_p95_m", s.h_err_p95_m},
                              {"h_err_rmse_m", s.h_err_rmse_m},
                              {"v_err_median_m", s.v_err_median_m}};
    std::cout << j.dump() << std::endl;
  } else {
    print_text(s, fixes);
  }
  return kExitOk;
}

}  // namespace

void add_gnss_command(CLI::App& app, int& exit_code) {
  CLI::App* gnss = app.add_subcommand("gnss", "GNSS receiver tools");
  gnss->require_subcommand(1);
  auto o = std::make_shared<GnssSolveOptions>();
  CLI::App* solve = gnss->add_subcommand(
      "solve", "Position fixes from pseudoranges (smartLoc text format) and their error against the ground truth");
  solve->add_option("INPUT", o->input, "smartLoc *_Input*.txt (pseudorange3 lines)")->required();
  solve->add_option("--gt", o->gt, "smartLoc *_GT*.txt (point3 lines)")->required()->type_name("GT");
  solve->add_option("--out", o->out, "Write the fixes (ECEF, WGS84, std in ENU, errors)")->type_name("FIXES.csv");
  solve->add_flag("--json", o->json, "Print one JSON object: epochs, fixes, h_err_median_m, h_err_p95_m, ...");
  solve->add_option("--config", o->config, "Receiver config (YAML with a `receiver:` section)")->type_name("FILE.yaml");
  solve->callback([o, &exit_code] { exit_code = run_gnss_solve(*o); });
  add_gnss_errors_command(*gnss, exit_code);
}

}  // namespace twinslam::cli
