#pragma once
// Point-to-plane ICP of paper eq. (2): Gauss-Newton on SE(3) with a Geman-McClure kernel and a correspondence gate
// that shrinks with the residuals (after KISS-ICP's adaptive threshold: gate = 3 sigma, kernel scale = sigma).
//
// Pivot. Every point is taken relative to the keyframe body position c = p_WB (not W's origin): a_j = x_j - c,
// b_j = q_j - c. The residual is r_j = n_j . (dR a_j + dp - b_j) (eq. 2). The correction therefore acts as
//   x' = dR (x - c) + c + dp,   i.e.  correction_W = [dR | c + dp - dR c]  (a transform of W, the dT of eq. 3).
// Applied to the keyframe pose (eq. 5: T_WB = dT T^_WB) this gives R_WB = dR R^_WB and p_WB = p^_WB + dp exactly:
// dp is the body position's correction and dR a rotation about the body, expressed in W. With W's origin as pivot
// instead, a small rotation error would move the body by |dR - I| |p_WB| and couple rotation into translation by an
// amount that depends on where the twin's origin happens to be.
//
// Linearization (left perturbation): x' = Exp(w) (dR a + dp) + v ~ a' + w x a' + v, so dr_j/d(w, v) =
// [(a'_j x n_j)^T, n_j^T]: the A_j of eq. (9) up to sign, in (rotation, translation) order.
//
// Weights. A landmark's residual has the variance of the twin surface (surface_sigma_m^2) plus its own along the
// normal, n^T C_j n (the estimator's covariance of the landmark: its depth from a short baseline is poor). Each
// residual is weighted by w_j = surface^2 / (surface^2 + n^T C_j n), 1 for a perfect landmark: the paper weighs every
// landmark the same, and VIO depths 40 m away are metres off (measured on city-loops: median |depth error| 0.85 m at
// 30-45 m, 0.15-0.2 m at 10-20 m).
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/registration/registration_config.hpp"
#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Correspondence {
  Eigen::Vector3d a;      // source point with the current correction, relative to the pivot: s dR a_j + dp [m]
  Eigen::Vector3d b;      // twin point relative to the pivot [m]
  Eigen::Vector3d n;      // twin normal (unit)
  double residual = 0.0;  // n . (a - b): the point-to-plane residual of eq. (2) [m]
  double distance = 0.0;  // |a - b| [m]
  double weight = 1.0;    // w_j (see above) [-]
};

// Weight of a landmark with covariance `cov_W` (zero: unknown, weight 1) matched to a twin plane of normal `n_W`.
double residual_weight(const RegistrationConfig& config, const Eigen::Matrix3d& cov_W, const Eigen::Vector3d& n_W);

struct IcpResult {
  Eigen::Matrix3d dR = Eigen::Matrix3d::Identity();                // rotation about the pivot (see above)
  Eigen::Vector3d dp = Eigen::Vector3d::Zero();                    // translation of the pivot [m, W]
  double scale = 1.0;  // of the cloud about the pivot (RegistrationConfig::estimate_scale; else 1), not in correction_W
  Eigen::Isometry3d correction_W = Eigen::Isometry3d::Identity();  // [dR | c + dp - dR c], dT of eq. (3)
  Eigen::Vector3d pivot_W = Eigen::Vector3d::Zero();               // c [m, W]
  int iterations = 0;
  bool converged = false;               // the last update was below the convergence thresholds
  double threshold_m = 0.0;             // the final correspondence gate [m]
  double sigma_m = 0.0;                 // robust sigma of the final weighted residuals sqrt(w_j) r_j [m]
  std::vector<Correspondence> inliers;  // at the final correction: distance <= gate and sqrt(w) |r| <= 3 sigma
  std::size_t correspondences = 0;      // at the final correction within the gate (inliers and the rest)
  double rmse_m = 0.0;                  // RMSE of the inliers' point-to-plane residuals (gamma of eq. 10) [m]
};

// The correction as a transform of W: x' = dR (x - pivot) + pivot + dp.
Eigen::Isometry3d correction_about(const Eigen::Matrix3d& dR, const Eigen::Vector3d& dp,
                                   const Eigen::Vector3d& pivot_W);

// A prior on the cloud's log-scale (7-DoF ICP only): ln s ~ N(log_scale, sigma^2). ICP adds it to eq. (2) as one more
// residual, (ln s - log_scale) / sigma in units of the kernel's sigma, so it weighs like that many inliers' worth of
// scale information rather than a fixed amount.
struct ScalePrior {
  double log_scale = 0.0;  // [-]
  double sigma = 0.0;      // [-] > 0
};

// Starts at the correction dR0 about the pivot (identity: the estimator's T_WL as it is). cov_W: the covariance of
// each p_W [m^2] (empty: unknown, every weight 1). Deterministic.
IcpResult run_icp(const RegistrationConfig& config, const TwinTileIndex& index, const std::vector<Eigen::Vector3d>& p_W,
                  const std::vector<Eigen::Matrix3d>& cov_W, const Eigen::Vector3d& pivot_W,
                  const Eigen::Matrix3d& dR0 = Eigen::Matrix3d::Identity(),
                  const std::optional<ScalePrior>& scale_prior = std::nullopt);

}  // namespace twinslam::registration
