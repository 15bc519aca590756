#pragma once
// The map registration factor (paper eqs. 3-7) through the world alignment: a registration of keyframe k's landmark
// cloud to the digital twin says that the keyframe's world pose, as estimated when its LocalMap was published
// (T^_WB = T^_WL T^_LB), is off by the correction dT (eq. 3: dT maps the estimate's world points onto the twin):
//   T_WB_meas = (dR, dp) applied about the keyframe position c = p^_WB:  R_WB_meas = dR R^_WB,  p_WB_meas = c + dp.
// The registration's information H (6x6, eqs. 8-10) is for [dtheta_W, dp_W] (rotation first, a world-frame rotation
// about c, then a translation in W) — the order and meaning of IDL Registration.information.
//
// Residual (6, rotation first, in W):
//   e = S [ Log(R_WB(x) R_WB_meas^T) ; p_WB(x) - p_WB_meas ],   R_WB(x) = Rz(yaw_WL) R_LB,  p_WB(x) = Rz p_LB + p_WL,
// with S = L^1/2 V^T from the eigen-decomposition H = V L V^T (eigenvalues below zero clamped to zero): a rank-
// deficient information (a direction the twin does not constrain, e.g. along a straight facade) is valid and gives
// no information there, where a Cholesky factor (the paper code's) would fail. Blocks: pose [7], T_WL [4].
// Compared with eq. (7), which measures T_LB with T_WL held fixed, this lets registrations refine T_WL (paper
// Sec. III-D: "T_WL is estimated"), and keeps the measurement in W where the twin is.
#include <string>

#include <ceres/cost_function.h>
#include <Eigen/Geometry>

namespace twinslam::estimator {

struct MapRegistration {
  std::int64_t keyframe_stamp_ns = 0;
  Eigen::Isometry3d T_WB_estimate = Eigen::Isometry3d::Identity();  // T^_WB when the cloud was published
  Eigen::Matrix3d dR_W = Eigen::Matrix3d::Identity();                // correction rotation (about the keyframe)
  Eigen::Vector3d dp_W = Eigen::Vector3d::Zero();                    // correction translation of the keyframe [m]
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  // [dtheta_W, dp_W]
  // The measured world pose T_WB_meas defined above.
  Eigen::Isometry3d measured_T_WB() const;
};

// From a correction given as a rigid transform of world points p' = dT p (about W's origin, as on the wire): the
// same correction about the keyframe position c: dR = R(dT), dp = dT c - c.
MapRegistration map_registration_from_correction(std::int64_t keyframe_stamp_ns, const Eigen::Isometry3d& T_WB_estimate,
                                                 const Eigen::Isometry3d& dT_W,
                                                 const Eigen::Matrix<double, 6, 6>& information);

// Why a registration from the wire cannot be fused, or "" when it can: a correction that is not finite or whose
// rotation is not one, an information matrix that is not finite, not symmetric (relative 1e-6) or not positive
// semi-definite (an eigenvalue below -1e-9 of the largest). Fusing any of these would put NaN or a negative weight
// into the window (issue 15: "a Registration with a non-symmetric or NaN information matrix").
std::string registration_problem(const Eigen::Isometry3d& dT_W, const Eigen::Matrix<double, 6, 6>& information);

// S with S^T S = H for a symmetric positive semi-definite H (negative eigenvalues from round-off clamped to zero).
Eigen::Matrix<double, 6, 6> information_square_root(const Eigen::Matrix<double, 6, 6>& H);

// The factor; the caller owns the result.
ceres::CostFunction* new_map_registration_factor(const MapRegistration& m);

// The estimator's keyframe covariance as pose_covariance_world() gives it, [dp_W (m), dtheta_B (rad)] (translation
// first, right perturbation), in a Registration's order and perturbation: (dtheta_W, dp_W) with dtheta_W =
// R_WB dtheta_B (rotation first, left perturbation in W). What LocalMap.T_WB_covariance carries.
Eigen::Matrix<double, 6, 6> to_registration_order(const Eigen::Matrix<double, 6, 6>& cov_pW_thetaB,
                                                  const Eigen::Matrix3d& R_WB);

}  // namespace twinslam::estimator
