#pragma once
// The two faces of an EvalResult: the JSON object of CONTRACTS.md (`twinslam eval --json`, `bench/metrics.json`) and
// a short human-readable table.
#include <string>

#include <nlohmann/json.hpp>

#include "twinslam/eval/evaluate.hpp"

namespace twinslam::eval {

// Contract keys: align, n, length_m, ate_pos_rmse_m, ate_rot_rmse_deg, ate_pos_max_m,
// rpe{key: {trans_pct, rot_deg_per_m}} (means over segments; null when the trajectory is shorter than the segment).
// Extra keys: n_gt, n_est, align_pairs, scale, ate_pos/ate_rot (full stats), rpe[key].{length_m, n, *_median}.
nlohmann::json to_json(const EvalResult& result);

// A few lines: ATE table (rmse, mean, median, std, min, max) and one RPE line per segment length.
std::string format_table(const EvalResult& result);

}  // namespace twinslam::eval
