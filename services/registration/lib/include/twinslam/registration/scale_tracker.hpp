#pragma once
// One vehicle's slowly varying cloud scale, as a prior for its next 7-DoF ICP (registration_config.hpp:
// scale_prior_walk). Why: a building moved since the twin was made pulls a 7-DoF registration's scale as far as it
// can, and a scale about the keyframe moves the keyframe: on the tiny flight with one building shifted 3 m (exact twin
// otherwise) the scale fell from 1.01 to 0.95 in 2 s and stayed there 13 s, and 10 of 53 accepted registrations ended
// > 0.5 m off. Rigid ICP (no scale) has 2 of 94 there but turns the VIO's real scale error into keyframe error
// elsewhere (city-survey 0.78 -> 1.86 m). A prior that follows the registrations before holds the odd clouds back and
// lets a slow change of the VIO scale through.
//
// The filter: ln s with a random walk of scale_prior_walk [1/sqrt(s)] between keyframes; after each accepted
// registration the tracked ln s is that registration's ICP result (which already weighed this prior against the
// twin), and its variance the Kalman update of the predicted one with scale_prior_measurement_sigma. Feeding ICP's
// prior-weighted result back makes it a strong low-pass filter; that is the point. Measured: updating instead with
// what the twin alone said (the prior taken back out, innovation-gated at 3 sigma) let the building's pull through,
// because it grows over a few keyframes (8 of 70 > 0.5 m).
//
// When it applies (scale_prior_applies): only to keyframes the estimator is settled on (heading and position sigma
// of LocalMap.T_WB_covariance below scale_prior_max_*). Before that, the twin corrections being fused still reshape
// the VIO map, and its scale with it, within seconds: on delft-loops the first registrations say 1.02 and, as the
// keyframe heading sigma falls from 0.5 to 0.24 deg (17-27 s), 1.00; a prior from 17 s held 1.02 for 10 s and 8 of
// 264 registrations ended 0.5-0.87 m off (none with the gate: 0 of 262). The tracker follows every accepted
// registration either way. Rejected registrations do not move it. Keyframe stamps out of order (a replayed or
// reordered LocalMap) are taken by |dt|.
#include <cstdint>
#include <optional>

#include "twinslam/registration/icp.hpp"
#include "twinslam/registration/registration_config.hpp"

namespace twinslam::registration {

// Whether the scale prior applies to a keyframe with this covariance (rotation first, LocalMap.T_WB_covariance):
// heading sigma (about W's z) below scale_prior_max_heading_sigma_deg and sqrt(trace) of the position block below
// scale_prior_max_position_sigma_m. No covariance: no.
bool scale_prior_applies(const RegistrationConfig& config, const std::optional<Matrix6d>& keyframe_covariance);

class ScaleTracker {
 public:
  explicit ScaleTracker(const RegistrationConfig& config) : config_(config) {}

  // The prior for a keyframe at stamp_ns; nullopt before the first accepted registration, when the prior is off
  // (scale_prior_walk 0) or ICP estimates no scale.
  std::optional<ScalePrior> prior(std::int64_t stamp_ns) const;
  // After the registration at stamp_ns: `scale` is its ICP scale (RegistrationResult::scale), used only when
  // `accepted`, finite and > 0.
  void update(std::int64_t stamp_ns, bool accepted, double scale);

 private:
  double predicted_variance(std::int64_t stamp_ns) const;

  RegistrationConfig config_;
  bool has_ = false;
  double log_scale_ = 0.0;
  double variance_ = 0.0;
  std::int64_t stamp_ns_ = 0;
};

}  // namespace twinslam::registration
