#pragma once
// Information of a registration: the 6x6 weight W_m of the map-registration factor (paper Sec. III-C2, eqs. 8-10).
//
// The 6-vector. Everything here is ordered xi = (w, v): rotation vector w [rad] first, then translation v [m] (the
// order of idl Registration.information; note that twinslam_geometry's se3 tangent is (translation, rotation)). A
// perturbation xi of the correction acts on world points as  x'' = Exp(w) (x' - c) + c + v  (x' a corrected point)
// about the keyframe body position c = p_WB (icp.hpp), so for the keyframe pose (eq. 5, T_WB = dT T~_WB):
// R_WB <- Exp(w) R_WB (w: a world-frame rotation about the body, a left perturbation of R_WB), p_WB <- p_WB + v. With
// T~_WB the keyframe pose the cloud was expressed with (T_WL T_LB of the input), the measurement is R^_WB = dR R~_WB,
// p^_WB = p~_WB + dp, and the estimator's factor is e = (Log(R_WB R^_WB^T), p_WB - p^_WB) (rotation first) with
// `information` below. The rotation acts about p_WB, not about W's origin: that is what keeps e's rotation and
// translation decoupled.
//
// H (eqs. 8-9) = sum_j A_j^T A_j over the inliers, A_j = [(a_j x n_j)^T, n_j^T] with a_j relative to c and a x n NOT
// normalized: units [m^2] in the rotation block, [m] off-diagonal, [1] in the translation block. The adaptive weighting
// uses H_w = sum_j w_j A_j^T A_j with the residual weights of icp.hpp (each landmark's own uncertainty).
#include <array>
#include <vector>

#include "twinslam/registration/icp.hpp"
#include "twinslam/registration/registration_config.hpp"

namespace twinslam::registration {

struct Information {
  Matrix6d H = Matrix6d::Zero();            // eq. (9), unweighted, (rotation, translation)
  Matrix6d H_weighted = Matrix6d::Zero();   // sum w_j A_j^T A_j (adaptive), (rotation, translation)
  Matrix6d information = Matrix6d::Zero();  // the weight W_m of the selected mode, (rotation, translation)
  // Eigen-analysis of the per-point normalized H_w: Hn = S H_w S / sum w_j, S = diag(1/L, 1/L, 1/L, 1, 1, 1), L = RMS
  // distance of the inliers from c. Scaling rotation by L makes the blocks comparable (a rotation w moves points by
  // ~L |w|), and dividing by the summed weight makes the value a per-point observability in [0, 1] (translation: the
  // weighted mean of n n^T), independent of how many landmarks the keyframe has.
  Vector6d eigenvalues = Vector6d::Zero();  // of Hn, ascending [-]
  Matrix6d directions = Matrix6d::Zero();   // column i: unit direction in xi space (= S u_i normalized) of eigenvalue i
  std::array<bool, 6> zeroed{};             // eigenvalue i < degeneracy_threshold
  int zero_directions = 0;                  // how many are zeroed
  double length_scale_m = 1.0;              // L (at least 1 m)
  double sigma_sq = 0.0;                    // paper: trace(H) (eq. 10's sigma^2); adaptive: the residual variance [m^2]
  int surfaces = 0;                         // twin planes the inliers lie on (adaptive with surface_error_m > 0)
};

// Groups inliers by the twin plane they matched: an inlier joins the first group whose first member's normal is within
// angle_deg of its own and whose plane (that member's n and b) passes within offset_m of its b; otherwise it starts a
// group. Returns each inlier's group, numbered 0, 1, ... in order of first appearance. Opposite normals (the two sides
// of a wall) are different surfaces.
std::vector<int> group_surfaces(const std::vector<Correspondence>& inliers, double angle_deg, double offset_m);

// eq. (8)-(9): sum of A_j^T A_j over the correspondences; `weighted`: of w_j A_j^T A_j.
// marginalize_scale: with a 7-DoF ICP (RegistrationConfig::estimate_scale), the Schur complement over the log-scale.
Matrix6d registration_hessian(const std::vector<Correspondence>& inliers, bool weighted = false,
                              bool marginalize_scale = false);

// Weights `inliers` (at the converged correction) as config.weights says:
//   paper:    beta / trace(H) * exp(-rmse^2 / 2) * H                                       (eq. 10 as written)
//   adaptive: H_w / sigma^2 with sigma^2 = max(robust_sigma, min_sigma)^2 * correlation_inflation, and the eigen-
//             directions of Hn below degeneracy_threshold removed (information exactly 0 along them). With
//             surface_error_m > 0, the inverse of the covariance the correction has when, besides that independent
//             noise, every twin plane the inliers lie on (group_surfaces) is offset along its normal by its own
//             N(0, surface_error_m^2): Cov = H_w^+ (surface_error_m^2 sum_k G_k G_k^T + sigma^2 H_w) H_w^+ on the kept
//             directions, G_k = sum_{j on plane k} w_j A_j (the correction's response to plane k moving by 1 m)
//   fixed:    diag(fixed_rotation_information x3, fixed_translation_information x3)
// robust_sigma_m: the robust sigma of the inliers' weighted residuals (IcpResult::sigma_m). Empty input gives all
// zeros.
Information compute_information(const RegistrationConfig& config, const std::vector<Correspondence>& inliers,
                                double rmse_m, double robust_sigma_m);

}  // namespace twinslam::registration
