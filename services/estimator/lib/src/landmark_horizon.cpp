// LandmarkHorizon (see landmark_horizon.hpp).
#include "twinslam/estimator/landmark_horizon.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {
namespace {

bool at_least_as_good(const LandmarkEstimate& a, const LandmarkEstimate& b) {
  const double ta = a.cov_L.trace(), tb = b.cov_L.trace();
  if (ta > 0.0 && tb > 0.0) return ta <= tb;
  return a.quality >= b.quality;
}

}  // namespace

void LandmarkHorizonConfig::validate(const std::string& source) const {
  const auto fail = [&](const char* key, const std::string& what) {
    throw InputError(source + ": local_map key '" + key + "': " + what);
  };
  if (!std::isfinite(horizon_s) || horizon_s < 0.0) fail("horizon_s", "must be >= 0 s");
  if (!std::isfinite(horizon_m) || horizon_m <= 0.0) fail("horizon_m", "must be > 0 m");
  if (max_landmarks < 1) fail("max_landmarks", "must be >= 1");
}

LandmarkHorizon::LandmarkHorizon(const LandmarkHorizonConfig& config) : config_(config) { config_.validate(); }

void LandmarkHorizon::follow_window(const std::map<std::int64_t, Eigen::Isometry3d>& keyframes_T_LB) {
  if (config_.follow_window) {
    for (const auto& [stamp, T_now] : keyframes_T_LB) {  // oldest first
      const auto then = keyframes_.find(stamp);
      if (then == keyframes_.end()) continue;
      const Eigen::Isometry3d moved = T_now * then->second.inverse();
      for (auto& [id, s] : seen_) {
        s.current.p_L = moved * s.current.p_L;
        s.best.p_L = moved * s.best.p_L;
      }
      break;
    }
  }
  keyframes_ = keyframes_T_LB;
}

std::vector<LandmarkEstimate> LandmarkHorizon::update(std::int64_t stamp_ns, const Eigen::Vector3d& p_LB,
                                                      const std::vector<LandmarkEstimate>& window) {
  for (const LandmarkEstimate& l : window) {
    // Remember the estimate from when the landmark was best observed: its quality falls as the keyframes that saw it
    // leave the window (two observations left: quality <= 0.25), so its last report before leaving is its worst,
    // though the position is as good as when it had all of them. With covariances the best is the most certain one
    // (quality saturates at 5 deg of parallax, which leaves a point 50 m away 1-2 m deep).
    auto [it, added] = seen_.try_emplace(l.id, Seen{l, l, stamp_ns});
    if (!added && at_least_as_good(l, it->second.best)) it->second.best = l;
    it->second.current = l;
    it->second.last_stamp_ns = stamp_ns;
  }
  const auto horizon_ns = static_cast<std::int64_t>(std::llround(config_.horizon_s * 1e9));
  std::vector<const Seen*> kept;
  for (auto it = seen_.begin(); it != seen_.end();) {
    const Seen& s = it->second;
    if (stamp_ns - s.last_stamp_ns > horizon_ns) {
      it = seen_.erase(it);  // too old for any later keyframe as well
      continue;
    }
    if (s.last_stamp_ns == stamp_ns || (s.best.p_L - p_LB).norm() <= config_.horizon_m) kept.push_back(&s);
    ++it;
  }
  if (kept.size() > static_cast<std::size_t>(config_.max_landmarks)) {
    // The most recently seen first (the window's own are the most recent); ties by id: deterministic.
    std::stable_sort(kept.begin(), kept.end(),
                     [](const Seen* a, const Seen* b) { return a->last_stamp_ns > b->last_stamp_ns; });
    kept.resize(static_cast<std::size_t>(config_.max_landmarks));
    std::sort(kept.begin(), kept.end(), [](const Seen* a, const Seen* b) { return a->current.id < b->current.id; });
  }
  std::vector<LandmarkEstimate> out;
  out.reserve(kept.size());
  // The window's own landmarks as the window has them now; the others as they were best observed.
  for (const Seen* s : kept) out.push_back(s->last_stamp_ns == stamp_ns ? s->current : s->best);
  return out;
}

}  // namespace twinslam::estimator
