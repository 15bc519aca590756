#include "twinslam/gnss/fix_errors.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/eval/stats.hpp"
#include "twinslam/gnss/frames.hpp"

namespace twinslam::gnss {

std::vector<FixError> fix_errors(const std::vector<Fix>& fixes, const std::vector<TruthPoint>& truth,
                                 double max_gap_s) {
  std::vector<FixError> out;
  for (const Fix& f : fixes) {
    if (!f.valid) continue;
    const auto it = std::lower_bound(truth.begin(), truth.end(), f.t_s,
                                     [](const TruthPoint& p, double t) { return p.t_s < t; });
    const TruthPoint* best = nullptr;
    if (it != truth.end()) best = &*it;
    if (it != truth.begin() && (best == nullptr || f.t_s - std::prev(it)->t_s < best->t_s - f.t_s)) {
      best = &*std::prev(it);
    }
    if (best == nullptr || std::abs(best->t_s - f.t_s) > max_gap_s) continue;
    const Geodetic g = ecef_to_geodetic(best->p_ecef);
    const Eigen::Vector3d d = rotation_enu_from_ecef(g.latitude_deg, g.longitude_deg) * (f.p_ecef - best->p_ecef);
    out.push_back(FixError{f.t_s, d.head<2>().norm(), std::abs(d.z())});
  }
  return out;
}

FixErrorStats fix_error_stats(std::size_t epochs, const std::vector<FixError>& errors) {
  FixErrorStats s;
  s.epochs = epochs;
  s.fixes = errors.size();
  std::vector<double> h, v;
  for (const FixError& e : errors) {
    h.push_back(e.horizontal_m);
    v.push_back(e.vertical_m);
  }
  s.h_err_median_m = eval::quantile(h, 0.5);
  s.h_err_p95_m = eval::quantile(h, 0.95);
  s.h_err_rmse_m = eval::compute_stats(h).rmse;
  s.v_err_median_m = eval::quantile(v, 0.5);
  return s;
}

}  // namespace twinslam::gnss
