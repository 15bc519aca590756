#include "twinslam/eval/rpe.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/eval/ate.hpp"

namespace twinslam::eval {
namespace {

// Index j > i with dist[j] - dist[i] closest to L, or i when no j lies within the tolerance.
std::size_t segment_end(const std::vector<double>& dist, std::size_t i, double L) {
  const double target = dist[i] + L;
  const auto it = std::lower_bound(dist.begin() + static_cast<std::ptrdiff_t>(i) + 1, dist.end(), target);
  std::size_t best = i;
  double best_err = kRpeLengthTolerance * L;
  const auto consider = [&](std::size_t j) {
    if (j <= i || j >= dist.size()) return;
    const double err = std::abs(dist[j] - target);
    if (err <= best_err) {
      best_err = err;
      best = j;
    }
  };
  const auto j = static_cast<std::size_t>(it - dist.begin());
  consider(j - 1);
  consider(j);
  return best;
}

}  // namespace

std::vector<double> cumulative_distance(const std::vector<Eigen::Isometry3d>& T_WB) {
  std::vector<double> dist(T_WB.size(), 0.0);
  for (std::size_t k = 1; k < T_WB.size(); ++k) {
    dist[k] = dist[k - 1] + (T_WB[k].translation() - T_WB[k - 1].translation()).norm();
  }
  return dist;
}

std::vector<RpeSegment> compute_rpe(const std::vector<Eigen::Isometry3d>& T_WB_gt,
                                    const std::vector<Eigen::Isometry3d>& T_WB_est,
                                    const std::vector<std::pair<std::string, double>>& lengths_m) {
  const std::vector<double> dist = cumulative_distance(T_WB_gt);
  std::vector<RpeSegment> out;
  for (const auto& [key, L] : lengths_m) {
    RpeSegment seg;
    seg.key = key;
    seg.length_m = L;
    for (std::size_t i = 0; L > 0.0 && i + 1 < dist.size(); ++i) {
      const std::size_t j = segment_end(dist, i, L);
      if (j == i) continue;
      const Eigen::Isometry3d T_gt_ij = T_WB_gt[i].inverse() * T_WB_gt[j];
      const Eigen::Isometry3d T_est_ij = T_WB_est[i].inverse() * T_WB_est[j];
      const Eigen::Isometry3d E = T_gt_ij.inverse() * T_est_ij;
      const double travelled_m = dist[j] - dist[i];
      seg.trans_pct.push_back(100.0 * E.translation().norm() / travelled_m);
      seg.rot_deg_per_m.push_back(rotation_angle_deg(E.linear()) / travelled_m);
    }
    seg.trans_pct_stats = compute_stats(seg.trans_pct);
    seg.rot_deg_per_m_stats = compute_stats(seg.rot_deg_per_m);
    out.push_back(std::move(seg));
  }
  return out;
}

}  // namespace twinslam::eval
