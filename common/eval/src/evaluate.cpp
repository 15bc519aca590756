#include "twinslam/eval/evaluate.hpp"

#include <algorithm>
#include <cstdio>

#include "twinslam/core/error.hpp"

namespace twinslam::eval {
namespace {

std::string name_of(const Trajectory& t, const char* fallback) { return t.source.empty() ? fallback : t.source; }

std::string span_s(const Trajectory& t) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "[%.3f, %.3f] s", t.poses.front().stamp_ns * 1e-9, t.poses.back().stamp_ns * 1e-9);
  return buf;
}

// "50m" / "100m", "10%": printed without trailing zeros, the spelling of CONTRACTS.md.
std::string length_key(double value, const char* unit) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g%s", value, unit);
  return buf;
}

}  // namespace

void EvalConfig::validate() const {
  if (max_dt_ns <= 0) throw UsageError("association window must be positive");
  for (double L : rpe_lengths_m) {
    if (!(L > 0.0)) throw UsageError("RPE segment lengths must be positive");
  }
  for (double f : rpe_fractions) {
    if (!(f > 0.0 && f <= 1.0)) throw UsageError("RPE length fractions must be in (0, 1]");
  }
}

EvalResult evaluate(const Trajectory& gt, const Trajectory& est, const EvalConfig& config) {
  config.validate();
  if (gt.empty()) throw InputError(where(name_of(gt, "ground truth"), 0, "no poses"));
  if (est.empty()) throw InputError(where(name_of(est, "estimate"), 0, "no poses"));
  const std::vector<Match> matches = associate(gt, est, config.max_dt_ns);
  if (matches.empty()) {
    throw InputError("no estimate pose within " + std::to_string(config.max_dt_ns / 1'000'000) +
                     " ms of a ground-truth pose: " + name_of(est, "estimate") + " spans " + span_s(est) + ", " +
                     name_of(gt, "ground truth") + " spans " + span_s(gt));
  }
  EvalResult r;
  r.align = config.align;
  r.n_gt = gt.size();
  r.n_est = est.size();
  r.n = matches.size();
  std::vector<Eigen::Isometry3d> T_LB(r.n);
  r.T_WB_gt.resize(r.n);
  r.stamp_ns.resize(r.n);
  for (std::size_t k = 0; k < r.n; ++k) {
    r.T_WB_gt[k] = gt.poses[matches[k].gt].T_XB;
    T_LB[k] = est.poses[matches[k].est].T_XB;
    r.stamp_ns[k] = est.poses[matches[k].est].stamp_ns;
  }
  r.align_pairs = config.align_first == 0 ? r.n : std::min(config.align_first, r.n);
  const auto first = static_cast<std::ptrdiff_t>(r.align_pairs);
  r.S_WL = align(config.align, {T_LB.begin(), T_LB.begin() + first}, {r.T_WB_gt.begin(), r.T_WB_gt.begin() + first});
  if (config.align == AlignMode::None) r.align_pairs = 0;
  r.T_WB_est.resize(r.n);
  for (std::size_t k = 0; k < r.n; ++k) r.T_WB_est[k] = r.S_WL.apply(T_LB[k]);

  r.ate = compute_ate(r.T_WB_gt, r.T_WB_est);
  const std::vector<double> dist = cumulative_distance(r.T_WB_gt);
  r.length_m = dist.back();
  std::vector<std::pair<std::string, double>> lengths;
  for (double L : config.rpe_lengths_m) lengths.emplace_back(length_key(L, "m"), L);
  for (double f : config.rpe_fractions) lengths.emplace_back(length_key(100.0 * f, "%"), f * r.length_m);
  r.rpe = compute_rpe(r.T_WB_gt, r.T_WB_est, lengths);
  return r;
}

}  // namespace twinslam::eval
