#pragma once
// Online calibration of the camera's rotation in the body frame, R_BC, in the sliding window (as VINS-Mono and OKVIS
// estimate their extrinsics). A rotation error of the camera mounting is not seen by the IMU or by the bearings alone:
// the estimate rotates the body to fit the camera, so every attitude is off by the calibration error (0.5 deg of it
// left ATE_R at 0.5-1.2 deg on the realistic scenarios). Rotations of the vehicle about other axes than the error's,
// gravity and the twin's registrations make it observable.
//
// The block: phi [3, rad], R_BC = R_BC0 Exp(phi), a right (camera-side) perturbation of the nominal R_BC0 of the
// dataset's sensor.yaml. Euclidean, so the marginalization keeps it like any other block; the translation t_BC stays
// as calibrated (a few millimetres matter little at landmark depths of metres to tens of metres).
#include <memory>

#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>
#include <Eigen/Geometry>

#include "twinslam/estimator/reprojection_factor.hpp"

namespace twinslam::estimator {

constexpr int kCameraRotationSize = 3;

// T_BC0 with its rotation corrected by phi (3 values, rad): R_BC0 Exp(phi), t_BC0.
Eigen::Isometry3d calibrated_T_BC(const Eigen::Isometry3d& T_BC0, const double* phi);

// ReprojectionFactor with the camera rotation correction as a fourth block: [anchor pose 7, observer pose 7,
// inverse depth 1, phi 3]. The Jacobian w.r.t. phi is exact for any phi (the right Jacobian of SO(3) maps the
// perturbation at R_BC to phi's coordinates).
class CameraRotationFactor final
    : public ceres::SizedCostFunction<2, kPoseSize, kPoseSize, kInverseDepthSize, kCameraRotationSize> {
 public:
  CameraRotationFactor(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_Cj, const Eigen::Isometry3d& T_BC0,
                       double sqrt_information);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  // The factor without the rotation block, for the outlier test with the current R_BC.
  const ReprojectionFactor& reprojection() const { return base_; }

 private:
  ReprojectionFactor base_;
  Eigen::Matrix3d R_BC0_;
};

// The calibration prior r = phi / sigma: the mounting is known to about sigma [rad] per axis (> 0).
std::unique_ptr<ceres::CostFunction> new_camera_rotation_prior(double sigma_rad);

}  // namespace twinslam::estimator
