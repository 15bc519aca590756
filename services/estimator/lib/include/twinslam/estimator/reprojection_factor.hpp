#pragma once
// Visual factor of the sliding window on unit bearings, so one factor serves pinhole and fisheye (even > 90 deg off
// the optical axis) alike: the tracking front end unprojects pixels to bearings with the camera model once.
//
// Parameter blocks: anchor pose [7] = T_LB of the anchor keyframe, observing pose [7] = T_LB of keyframe j,
// inverse depth [1] (landmark.hpp). Camera extrinsics T_BC are fixed at construction; CameraRotationFactor
// (camera_calibration.hpp) estimates a correction of their rotation with the same prediction (evaluate_with()).
//
// Prediction (homogeneous, scaled by rho so that rho -> 0, a point at infinity, stays finite; the visual residual of
// VINS-Mono, Sec. VI, up to the scale):
//   h = rho p_Cj = R_CB ( R_LBj^T ( R_LBa (R_BC f_Ca + rho t_BC) + rho (p_La - p_Lj) ) - rho t_BC ),   b = h / |h|.
// Residual: the tangent-plane error of the predicted bearing b against the observed bearing f_Cj,
//   r = s [t1 t2]^T (b - f_Cj),
// with [t1 t2] an orthonormal basis of the plane orthogonal to f_Cj (the unit-sphere error of VINS-Mono's projection
// factor and of OpenVINS/Basalt's bearing models). |[t1 t2]^T (b - f)| = sin(angle(b, f)) ~= the angular error [rad];
// s = focal_px / pixel_sigma turns it into pixel-equivalent units whitened by the pixel noise.
// A prediction pointing away from f_Cj (angle > 90 deg) is also a minimum of this residual: cheirality is the caller's
// check (in_front()).
//
// The anchor's own observation needs no factor: with anchor == observer, h = R_CB R_BC f_Ca = f_Ca identically (the
// anchor bearing is the observation), i.e. a zero residual with zero Jacobians, by construction of the
// parameterization. (Ceres could not take the same pose block twice in one residual anyway.)
#include <ceres/loss_function.h>
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/landmark.hpp"

namespace twinslam::estimator {

// Orthonormal basis [t1 t2] (3x2) of the tangent plane of the unit sphere at f (both columns orthogonal to f).
Eigen::Matrix<double, 3, 2> tangent_basis(const Eigen::Vector3d& f);

// Noise model and robust loss of the reprojection factors (one config for the module; validate() checks it).
struct ReprojectionNoise {
  double focal_px = 460.0;     // px per radian near the optical axis (fu of the camera model) [px/rad]
  double pixel_sigma = 1.0;    // standard deviation of a tracked feature [px]
  // Huber threshold in whitened units (standard deviations). Huber, as VINS-Mono: convex, so it does not create
  // local minima near the solution; gross outliers are removed explicitly by their reprojection error instead.
  double huber_threshold = 1.0;

  void validate() const;  // throws twinslam::InputError naming the bad field
  double sqrt_information() const { return focal_px / pixel_sigma; }  // s [1/rad]
};

// The recommended robust loss for ReprojectionFactor residuals (caller owns it, or hands it to ceres::Problem).
ceres::LossFunction* new_reprojection_loss(const ReprojectionNoise& noise = {});

class ReprojectionFactor final : public ceres::SizedCostFunction<2, kPoseSize, kPoseSize, kInverseDepthSize> {
 public:
  // f_Ca: the landmark's anchor bearing (unit, anchor camera); f_Cj: the observation in keyframe j's camera (unit);
  // T_BC: camera in body; sqrt_information: s above (ReprojectionNoise::sqrt_information()).
  ReprojectionFactor(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_Cj, const Eigen::Isometry3d& T_BC,
                     double sqrt_information);

  // Jacobians w.r.t. the ambient coordinates, like ImuFactor: closed-form derivatives w.r.t. p_L + dp and the right
  // perturbation R_LB Exp(dtheta), times geometry::right_perturbation_jacobian(q) for the quaternion.
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  // The same with the camera rotation R_BC in place of the constructed one (t_BC stays). dr_dphi (2x3 row-major,
  // may be null) receives the Jacobian w.r.t. phi of R_BC Exp(phi) at phi = 0, the right perturbation of R_BC.
  bool evaluate_with(const Eigen::Matrix3d& R_BC, double const* const* parameters, double* residuals,
                     double** jacobians, double* dr_dphi) const;
  // The same with other bearings than the constructed ones (the lens calibration corrects both, lens_calibration.hpp):
  // anchor bearing f_Ca (unit) and observation f_obs, residual s [t1 t2]^T (b - f_obs) with the constructed f_Cj's
  // basis. dr_dfa, dr_dfo (2x3 row-major, may be null): Jacobians w.r.t. f_Ca and f_obs.
  bool evaluate_bearings(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_obs, double const* const* parameters,
                         double* residuals, double** jacobians, double* dr_dfa, double* dr_dfo) const;

  // h = rho p_Cj (see above) for the given blocks; R_BC null: the constructed rotation.
  Eigen::Vector3d predicted_scaled_point(const double* pose_a, const double* pose_j, double rho,
                                         const Eigen::Matrix3d* R_BC = nullptr) const;
  // Cheirality: the predicted point lies on the observed side (angle to f_Cj below 90 deg) and rho >= 0.
  bool in_front(const double* pose_a, const double* pose_j, double rho, const Eigen::Matrix3d* R_BC = nullptr) const;
  // Angle between predicted and observed bearings [rad], for outlier removal (times focal_px gives px).
  double angular_error(const double* pose_a, const double* pose_j, double rho,
                       const Eigen::Matrix3d* R_BC = nullptr) const;

  const Eigen::Vector3d& observed_bearing() const { return f_Cj_; }
  const Eigen::Vector3d& anchor_bearing() const { return f_Ca_; }

 private:
  // Every evaluate_*: R_BC, the anchor bearing, the observation (null: the constructed f_Cj, whose basis term is 0).
  struct Inputs {
    const Eigen::Matrix3d& R_BC;
    const Eigen::Vector3d& f_Ca;
    const Eigen::Vector3d* f_obs;
  };
  bool evaluate_impl(const Inputs& in, double const* const* parameters, double* residuals, double** jacobians,
                     double* dr_dphi, double* dr_dfa) const;
  Eigen::Vector3d f_Ca_, f_Cj_;
  Eigen::Matrix<double, 2, 3> scaled_basis_T_;  // s [t1 t2]^T
  Eigen::Matrix3d R_BC_;
  Eigen::Vector3d t_BC_;
};

}  // namespace twinslam::estimator
