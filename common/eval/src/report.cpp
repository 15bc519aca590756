#include "twinslam/eval/report.hpp"

#include <cstdio>

namespace twinslam::eval {
namespace {

nlohmann::json stats_json(const ErrorStats& s) {
  return {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std}, {"min", s.min}, {"max", s.max}};
}

// JSON has no NaN; an empty segment set is "no number", which null says honestly.
nlohmann::json number_or_null(const ErrorStats& s, double value) { return s.n == 0 ? nlohmann::json() : nlohmann::json(value); }

std::string line(const char* fmt, double a, double b, double c, double d, double e, double f, const char* name) {
  char buf[160];
  std::snprintf(buf, sizeof(buf), fmt, name, a, b, c, d, e, f);
  return buf;
}

}  // namespace

nlohmann::json to_json(const EvalResult& r) {
  nlohmann::json rpe = nlohmann::json::object();
  for (const auto& seg : r.rpe) {
    const auto& t = seg.trans_pct_stats;
    const auto& q = seg.rot_deg_per_m_stats;
    rpe[seg.key] = {{"trans_pct", number_or_null(t, t.mean)},
                    {"rot_deg_per_m", number_or_null(q, q.mean)},
                    {"trans_pct_median", number_or_null(t, t.median)},
                    {"rot_deg_per_m_median", number_or_null(q, q.median)},
                    {"length_m", seg.length_m},
                    {"n", t.n}};
  }
  return {{"align", to_string(r.align)},
          {"n", r.n},
          {"length_m", r.length_m},
          {"ate_pos_rmse_m", r.ate.pos.rmse},
          {"ate_rot_rmse_deg", r.ate.rot.rmse},
          {"ate_pos_max_m", r.ate.pos.max},
          {"rpe", rpe},
          {"n_gt", r.n_gt},
          {"n_est", r.n_est},
          {"align_pairs", r.align_pairs},
          {"scale", r.S_WL.scale},
          {"ate_pos", stats_json(r.ate.pos)},
          {"ate_rot", stats_json(r.ate.rot)}};
}

std::string format_table(const EvalResult& r) {
  char head[256];
  std::string out = "align " + to_string(r.align);
  if (r.align != AlignMode::None) {
    std::snprintf(head, sizeof(head), " (on %zu pairs, scale %.4f)", r.align_pairs, r.S_WL.scale);
    out += head;
  }
  std::snprintf(head, sizeof(head), "  associated %zu of %zu estimate poses  length %.1f m\n", r.n, r.n_est,
                r.length_m);
  out += head;
  const char* row = "%-12s %10.4f %10.4f %10.4f %10.4f %10.4f %10.4f\n";
  out += "ATE             rmse       mean     median        std        min        max\n";
  const auto& p = r.ate.pos;
  const auto& q = r.ate.rot;
  out += line(row, p.rmse, p.mean, p.median, p.std, p.min, p.max, "pos [m]");
  out += line(row, q.rmse, q.mean, q.median, q.std, q.min, q.max, "rot [deg]");
  out += "RPE          length [m]  segments  trans [%]  rot [deg/m]   (mean)\n";
  for (const auto& seg : r.rpe) {
    char buf[160];
    if (seg.trans_pct_stats.n == 0) {
      std::snprintf(buf, sizeof(buf), "%-12s %10.1f %9d %10s %12s\n", seg.key.c_str(), seg.length_m, 0, "-", "-");
    } else {
      std::snprintf(buf, sizeof(buf), "%-12s %10.1f %9zu %10.3f %12.5f\n", seg.key.c_str(), seg.length_m,
                    seg.trans_pct_stats.n, seg.trans_pct_stats.mean, seg.rot_deg_per_m_stats.mean);
    }
    out += buf;
  }
  return out;
}

}  // namespace twinslam::eval
