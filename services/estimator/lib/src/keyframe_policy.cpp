#include "twinslam/estimator/keyframe_policy.hpp"

#include <cmath>
#include <string>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {

void KeyframePolicyConfig::validate() const {
  if (!(min_mean_parallax_px > 0.0) || !std::isfinite(min_mean_parallax_px)) {
    throw InputError("KeyframePolicyConfig: min_mean_parallax_px must be > 0");
  }
  if (!(focal_px > 0.0) || !std::isfinite(focal_px)) throw InputError("KeyframePolicyConfig: focal_px must be > 0");
  if (!(min_tracked_ratio > 0.0 && min_tracked_ratio <= 1.0)) {
    throw InputError("KeyframePolicyConfig: min_tracked_ratio must be in (0, 1]");
  }
}

std::string_view to_string(KeyframeReason reason) {
  switch (reason) {
    case KeyframeReason::kNone: return "none";
    case KeyframeReason::kParallax: return "parallax";
    case KeyframeReason::kTrackLoss: return "track loss";
  }
  return "unknown";
}

KeyframeDecision decide_keyframe(const KeyframePolicyConfig& config, const KeyframeInput& input) {
  KeyframeDecision out;
  double sum = 0.0;
  for (const auto& t : input.tracked) {
    const Eigen::Vector3d compensated = input.R_CkCc * t.f_Cc.normalized();  // the current ray in C_k
    const Eigen::Vector3d f_k = t.f_Ck.normalized();
    sum += std::atan2(f_k.cross(compensated).norm(), f_k.dot(compensated));  // [rad]
  }
  if (!input.tracked.empty()) out.mean_parallax_px = config.focal_px * sum / static_cast<double>(input.tracked.size());
  if (input.keyframe_features > 0) {
    out.tracked_ratio = static_cast<double>(input.tracked.size()) / static_cast<double>(input.keyframe_features);
  }
  if (out.tracked_ratio < config.min_tracked_ratio) {
    out.reason = KeyframeReason::kTrackLoss;
  } else if (out.mean_parallax_px > config.min_mean_parallax_px) {
    out.reason = KeyframeReason::kParallax;
  }
  out.is_keyframe = out.reason != KeyframeReason::kNone;
  return out;
}

}  // namespace twinslam::estimator
