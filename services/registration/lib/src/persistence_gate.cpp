// PersistenceGate (see persistence_gate.hpp).
#include "twinslam/registration/persistence_gate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace twinslam::registration {

bool PersistenceGate::agrees(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const Eigen::Vector3d& p_W) const {
  // b is the newest correction and p_W its keyframe: a large correction means a fast-drifting estimator, whose
  // corrections change by a share of themselves in a span.
  const double tolerance_m =
      std::max(config_.persistent_tolerance_m, config_.persistent_tolerance_fraction * (b * p_W - p_W).norm());
  const double angle_rad = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
  return angle_rad <= config_.persistent_tolerance_deg * M_PI / 180.0 && (a * p_W - b * p_W).norm() <= tolerance_m;
}

bool PersistenceGate::review(RegistrationResult& r, std::int64_t stamp_ns) {
  if (r.status != RegistrationStatus::kCorrectionTooLarge || config_.persistent_corrections == 0) return false;
  // Refusals older than two spans are stale. Accepted registrations in between do not end a run: one that moved the
  // estimate changes the corrections after it, which then disagree; a degenerate one that could not (its weak
  // directions zeroed) must not hide the drift along them.
  const std::int64_t stale_ns = stamp_ns - static_cast<std::int64_t>(2e9 * config_.persistent_span_s);
  refused_.erase(refused_.begin(), std::find_if(refused_.begin(), refused_.end(),
                                                [&](const Refusal& f) { return f.stamp_ns >= stale_ns; }));
  // The run: the newest refusals that all agree with this one (a drifting estimator's corrections change slowly).
  std::size_t first = refused_.size();
  while (first > 0 && agrees(refused_[first - 1].correction_W, r.correction_W, r.pivot_W)) --first;
  refused_.erase(refused_.begin(), refused_.begin() + static_cast<std::ptrdiff_t>(first));
  refused_.push_back({stamp_ns, r.correction_W});
  const double span_s = 1e-9 * static_cast<double>(stamp_ns - refused_.front().stamp_ns);
  if (refused_.size() < static_cast<std::size_t>(config_.persistent_corrections) || span_s < config_.persistent_span_s)
    return false;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "accepted: %zu keyframes over %.1f s in a row gave this correction (Mahalanobis distance^2 %.2f)",
                refused_.size(), span_s, r.mahalanobis_sq);
  refused_.clear();
  ++readmitted_;
  r.status = RegistrationStatus::kAccepted;
  r.information = r.details.information;
  r.reason = buf;
  return true;
}

}  // namespace twinslam::registration
