// `twinslam gnss errors DIR [--json]`: a dataset's GNSS fixes (mav0/gnss0/data.csv) against its ground truth, by
// height band above the ground (W's up axis: the simulator's ground is at U = 0), and, when the dataset has
// mav0/gnss0/pseudoranges.csv, the signals the receiver had (per epoch, share received directly).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "gnss_commands.hpp"
#include "dataset_twin.hpp"
#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/gnss/height_bands.hpp"
#include "twinslam/trajectory/io.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::cli {
namespace {

namespace fs = std::filesystem;

// The ground-truth position nearest in time (within 50 ms), or false.
bool truth_at(const Trajectory& gt, std::int64_t stamp, Eigen::Vector3d* p_W) {
  const auto it = std::lower_bound(gt.poses.begin(), gt.poses.end(), stamp,
                                   [](const StampedPose& p, std::int64_t t) { return p.stamp_ns < t; });
  const StampedPose* best = nullptr;
  for (auto c : {it, it == gt.poses.begin() ? it : std::prev(it)}) {
    if (c == gt.poses.end()) continue;
    if (best == nullptr || std::llabs(c->stamp_ns - stamp) < std::llabs(best->stamp_ns - stamp)) best = &*c;
  }
  if (best == nullptr || std::llabs(best->stamp_ns - stamp) > 50'000'000) return false;
  *p_W = best->p_X();
  return true;
}

struct SignalSummary {
  std::size_t epochs = 0, signals = 0, direct = 0;
};

SignalSummary read_signals(const fs::path& file) {
  SignalSummary s;
  if (!fs::exists(file)) return s;
  std::int64_t last = -1;
  read_csv(file, 10, [&](const CsvRow& row) {
    const std::int64_t t = parse_int64(file, row, 0, "timestamp");
    if (t != last) ++s.epochs;
    last = t;
    ++s.signals;
    s.direct += parse_int64(file, row, 9, "line_of_sight") != 0 ? 1 : 0;
  });
  return s;
}

int run_gnss_errors(const std::string& dir, bool json) {
  const fs::path root(dir);
  const twin::EnuFrame frame(read_dataset_geo(root).origin);
  const Trajectory gt = read_dataset_groundtruth(root);
  const fs::path fixes = root / "mav0/gnss0/data.csv";
  if (!fs::exists(fixes)) throw InputError(where(fixes.string(), 0, "missing (the dataset has no GNSS)"));
  std::vector<gnss::HeightSample> samples;
  read_csv(fixes, 8, [&](const CsvRow& row) {
    Eigen::Vector3d truth;
    if (!truth_at(gt, parse_int64(fixes, row, 0, "timestamp"), &truth)) return;
    const Eigen::Vector3d p_W = frame.from_lla(parse_double(fixes, row, 1, "latitude"),
                                               parse_double(fixes, row, 2, "longitude"),
                                               parse_double(fixes, row, 3, "altitude"));
    samples.push_back({truth.z(), (p_W - truth).head<2>().norm(), std::abs(p_W.z() - truth.z())});
  });
  const auto bands = gnss::errors_by_height(samples);
  const SignalSummary sig = read_signals(root / "mav0/gnss0/pseudoranges.csv");
  if (json) {
    nlohmann::json j = {{"fixes", samples.size()}, {"bands", nlohmann::json::array()}};
    for (const auto& b : bands) {
      j["bands"].push_back({{"band", b.name}, {"fixes", b.fixes}, {"h_median_m", b.h_median_m},
                            {"h_mean_m", b.h_mean_m}, {"h_p95_m", b.h_p95_m}, {"v_median_m", b.v_median_m}});
    }
    if (sig.epochs > 0) j["signals"] = {{"epochs", sig.epochs}, {"signals", sig.signals}, {"direct", sig.direct}};
    std::cout << j.dump() << std::endl;
    return kExitOk;
  }
  std::printf("%-10s %7s %10s %10s %10s %10s\n", "height [m]", "fixes", "h median", "h mean", "h p95", "v median");
  for (const auto& b : bands) {
    std::printf("%-10s %7zu %10.2f %10.2f %10.2f %10.2f\n", b.name.c_str(), b.fixes, b.h_median_m, b.h_mean_m,
                b.h_p95_m, b.v_median_m);
  }
  if (sig.epochs > 0) {
    std::printf("signals: %.1f per epoch over %zu epochs, %.1f %% direct\n",
                static_cast<double>(sig.signals) / static_cast<double>(sig.epochs), sig.epochs,
                100.0 * static_cast<double>(sig.direct) / static_cast<double>(sig.signals));
  }
  return kExitOk;
}

}  // namespace

void add_gnss_errors_command(CLI::App& gnss, int& exit_code) {
  auto dir = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = gnss.add_subcommand("errors", "A dataset's GNSS fixes against its ground truth, by height band");
  cmd->add_option("DIR", *dir, "Dataset folder (twinslam sim output or a recording with dataset.yaml)")->required();
  cmd->add_flag("--json", *json, "One JSON object: fixes, bands [{band, fixes, h_median_m, ...}], signals");
  cmd->callback([dir, json, &exit_code] { exit_code = run_gnss_errors(*dir, *json); });
}

}  // namespace twinslam::cli
