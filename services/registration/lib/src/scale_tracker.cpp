// The per-vehicle scale prior (see scale_tracker.hpp).
#include "twinslam/registration/scale_tracker.hpp"

#include <cmath>

namespace twinslam::registration {

bool scale_prior_applies(const RegistrationConfig& config, const std::optional<Matrix6d>& keyframe_covariance) {
  if (!keyframe_covariance) return false;
  const Matrix6d& P = *keyframe_covariance;
  const double heading_sigma_deg = std::sqrt(P(2, 2)) * 180.0 / M_PI;
  const double position_sigma_m = std::sqrt(P.block<3, 3>(3, 3).trace());
  // Written so that NaN compares false: a covariance that is not one never lets the prior apply.
  return heading_sigma_deg < config.scale_prior_max_heading_sigma_deg &&
         position_sigma_m < config.scale_prior_max_position_sigma_m;
}

double ScaleTracker::predicted_variance(std::int64_t stamp_ns) const {
  const double dt_s = std::abs(static_cast<double>(stamp_ns - stamp_ns_)) * 1e-9;
  return variance_ + config_.scale_prior_walk * config_.scale_prior_walk * dt_s;
}

std::optional<ScalePrior> ScaleTracker::prior(std::int64_t stamp_ns) const {
  if (!has_ || !config_.estimate_scale || !(config_.scale_prior_walk > 0.0)) return std::nullopt;
  return ScalePrior{log_scale_, std::sqrt(predicted_variance(stamp_ns))};
}

void ScaleTracker::update(std::int64_t stamp_ns, bool accepted, double scale) {
  if (!accepted || !(scale > 0.0) || !std::isfinite(scale)) return;
  const double R = config_.scale_prior_measurement_sigma * config_.scale_prior_measurement_sigma;
  variance_ = has_ ? 1.0 / (1.0 / predicted_variance(stamp_ns) + 1.0 / R) : R;
  log_scale_ = std::log(scale);
  stamp_ns_ = stamp_ns;
  has_ = true;
}

}  // namespace twinslam::registration
