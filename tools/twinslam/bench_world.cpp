#include "bench_world.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

namespace twinslam::cli {
namespace {

// The ground-truth pose nearest in time to t (ground truth is dense: 200 Hz in the simulator's datasets).
const StampedPose* nearest(const Trajectory& gt, std::int64_t t) {
  if (gt.empty()) return nullptr;
  auto it = std::lower_bound(gt.poses.begin(), gt.poses.end(), t,
                             [](const StampedPose& p, std::int64_t s) { return p.stamp_ns < s; });
  if (it == gt.poses.end()) return &gt.poses.back();
  if (it != gt.poses.begin() && t - std::prev(it)->stamp_ns < it->stamp_ns - t) --it;
  return &*it;
}

}  // namespace

std::optional<WorldStart> read_world_start(const std::filesystem::path& run_dir, const Trajectory& gt,
                                           const Trajectory& est) {
  const auto j = nlohmann::json::parse(std::ifstream(run_dir / "run.json"));
  if (!j.contains("aligned_from_stamp_ns") || j["aligned_from_stamp_ns"].is_null()) return std::nullopt;
  WorldStart w;
  w.aligned_from_stamp_ns = j["aligned_from_stamp_ns"].get<std::int64_t>();
  w.aligned_after_s = j["aligned_after_s"].is_null() ? 0.0 : j["aligned_after_s"].get<double>();
  const auto first_ns = w.aligned_from_stamp_ns - static_cast<std::int64_t>(std::llround(w.aligned_after_s * 1e9));
  const std::int64_t at = std::max<std::int64_t>(first_ns + 10'000'000'000LL, w.aligned_from_stamp_ns);
  const auto e = std::find_if(est.poses.begin(), est.poses.end(), [at](const auto& p) { return p.stamp_ns >= at; });
  if (const StampedPose* g = e == est.poses.end() ? nullptr : nearest(gt, e->stamp_ns)) {
    w.error_at_10s_m = (e->p_X() - g->p_X()).norm();
    w.error_at_10s_deg = Eigen::AngleAxisd(e->T_XB.linear() * g->T_XB.linear().transpose()).angle() * 180.0 / M_PI;
  }
  if (j.contains("out_of_world_ns")) {
    for (const auto& stretch : j["out_of_world_ns"]) {
      w.out_of_world_ns.emplace_back(stretch.at(0).get<std::int64_t>(), stretch.at(1).get<std::int64_t>());
    }
  }
  if (j.contains("registration_latency_ms")) {
    w.latency_median_ms = j["registration_latency_ms"]["median"].get<double>();
    w.latency_p99_ms = j["registration_latency_ms"]["p99"].get<double>();
  }
  return w;
}

void keep_world_poses(Trajectory& est, const WorldStart& start) {
  std::erase_if(est.poses, [&start](const StampedPose& p) {
    if (p.stamp_ns < start.aligned_from_stamp_ns) return true;
    return std::any_of(start.out_of_world_ns.begin(), start.out_of_world_ns.end(),
                       [&p](const auto& s) { return p.stamp_ns >= s.first && p.stamp_ns <= s.second; });
  });
}

}  // namespace twinslam::cli
