#include "twinslam/eval/association.hpp"

#include <algorithm>
#include <cstdlib>

namespace twinslam::eval {

std::vector<Match> associate(const Trajectory& gt, const Trajectory& est, std::int64_t max_dt_ns) {
  struct Candidate {
    std::int64_t abs_dt;
    Match match;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(2 * est.size());
  auto gt_before = gt.poses.begin();
  for (std::size_t i = 0; i < est.size(); ++i) {
    const std::int64_t t = est.poses[i].stamp_ns;
    // Both sequences are sorted, so the search window only moves forward.
    gt_before = std::lower_bound(gt_before, gt.poses.end(), t,
                                 [](const StampedPose& p, std::int64_t s) { return p.stamp_ns < s; });
    const auto first = static_cast<std::size_t>(gt_before - gt.poses.begin());
    for (std::size_t j : {first - 1, first}) {  // first - 1 wraps for first == 0 and fails the bound check
      if (j >= gt.size()) continue;
      const std::int64_t abs_dt = std::llabs(gt.poses[j].stamp_ns - t);
      if (abs_dt <= max_dt_ns) candidates.push_back({abs_dt, {j, i}});
    }
  }
  // Closest pairs first; stable so ties keep time order and the result is deterministic.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.abs_dt < b.abs_dt; });
  std::vector<char> gt_used(gt.size(), 0), est_used(est.size(), 0);
  std::vector<Match> matches;
  for (const auto& c : candidates) {
    if (gt_used[c.match.gt] || est_used[c.match.est]) continue;
    gt_used[c.match.gt] = est_used[c.match.est] = 1;
    matches.push_back(c.match);
  }
  // Strictly increasing stamps on both sides make greedy pairs non-crossing, so sorting by est sorts by gt too.
  std::sort(matches.begin(), matches.end(), [](const Match& a, const Match& b) { return a.est < b.est; });
  return matches;
}

}  // namespace twinslam::eval
