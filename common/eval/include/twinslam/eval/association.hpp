#pragma once
// Timestamp association of an estimate to the ground truth (CONTRACTS.md: closest stamp, |dt| <= 20 ms, each pose
// used at most once). No interpolation: the ground truth of our datasets is at least as dense as the estimate.
#include <cstdint>
#include <vector>

#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::eval {

constexpr std::int64_t kDefaultMaxDtNs = 20'000'000;  // 20 ms

struct Match {
  std::size_t gt = 0;   // index into the ground truth
  std::size_t est = 0;  // index into the estimate
};

// Pairs in increasing time order. Greedy on |dt| over each estimate's two neighbouring ground-truth poses, so a
// ground-truth pose that is the closest for two estimates goes to the closer one. O(n log n).
std::vector<Match> associate(const Trajectory& gt, const Trajectory& est, std::int64_t max_dt_ns = kDefaultMaxDtNs);

}  // namespace twinslam::eval
