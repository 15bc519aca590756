#pragma once
// One registration of a keyframe's landmarks to the twin (paper Sec. III-C): preprocess -> ICP (eq. 2) ->
// information (eqs. 8-10) -> acceptance. Every rejection has a status and a one-line reason; a rejected result still
// carries what was computed up to the rejection (for logs), but the estimator must not use its correction.
#include <optional>
#include <string>

#include "twinslam/registration/icp.hpp"
#include "twinslam/registration/information.hpp"
#include "twinslam/registration/preprocess.hpp"
#include "twinslam/registration/registration_config.hpp"
#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration {

enum class RegistrationStatus {
  kAccepted,
  kTooFewPoints,        // source points after preprocessing < min_points
  kNotConverged,        // ICP hit max_iterations (or lost its correspondences) before the update was small
  kTooFewInliers,       // inliers < min_inliers (also: no twin near the cloud)
  kFitnessTooLow,       // inliers / source points < min_fitness
  kRmseTooLarge,        // inlier RMSE > max_rmse_m
  kDegenerate,          // more than max_zero_directions poorly observed directions
  kCorrectionTooLarge,  // Mahalanobis distance of the correction under the prior covariance > max_mahalanobis_sq
};
const char* status_name(RegistrationStatus status);  // "accepted", "too_few_points", ...

struct StageTimes {
  double preprocess_ms = 0, icp_ms = 0, hessian_ms = 0, total_ms = 0;
};

struct RegistrationResult {
  RegistrationStatus status = RegistrationStatus::kTooFewPoints;
  std::string reason;                                              // empty when accepted (but see persistence_gate.hpp)
  Eigen::Isometry3d correction_W = Eigen::Isometry3d::Identity();  // dT of eq. (3) (icp.hpp: pivot and convention)
  Eigen::Vector3d pivot_W = Eigen::Vector3d::Zero();               // keyframe body position c [m, W]
  Vector6d correction_xi = Vector6d::Zero();  // (Log dR [rad], dp [m]) about the pivot, (rotation, translation)
  Matrix6d information = Matrix6d::Zero();    // W_m, (rotation, translation); zero unless accepted
  Vector6d information_eigenvalues = Vector6d::Zero();  // of the per-point normalized H, ascending (information.hpp)
  Information details;                                  // H, eigen-directions, which were zeroed
  double mahalanobis_sq = 0.0;                          // xi^T Sigma^-1 xi when a prior covariance was given
  double rmse_m = 0.0;
  std::size_t source_points = 0, inliers = 0;
  double fitness = 0.0;  // inliers / source points
  double scale = 1.0;    // ICP's scale of the cloud about the pivot (1 unless estimate_scale), not in correction_W
  int iterations = 0;
  int yaw_starts = 1;  // ICP runs: the heading search's starts (yaw_search.hpp), twice with a wider first gate; 1 when sure
  bool heading_ambiguous = false;  // refused because another heading fit almost as well (correction: the best one's)
  StageTimes time;

  bool accepted() const { return status == RegistrationStatus::kAccepted; }
};

// prior_covariance: the estimator's 6x6 covariance of the keyframe pose in the same (rotation [rad^2], translation
// [m^2]) order and convention as the correction (left rotation about p_WB, position in W); nothing skips that test.
// scale_prior: on ICP's log-scale (icp.hpp; scale_tracker.hpp keeps one per vehicle).
// Throws InputError for bad input (preprocess) or a covariance that is not finite, symmetric and positive definite.
RegistrationResult register_cloud(const RegistrationConfig& config, const TwinTileIndex& index,
                                  const SourceInput& source,
                                  const std::optional<Matrix6d>& prior_covariance = std::nullopt,
                                  const std::optional<ScalePrior>& scale_prior = std::nullopt);

}  // namespace twinslam::registration
