#include "twinslam/estimator/camera_calibration.hpp"

#include <stdexcept>

#include <ceres/normal_prior.h>

#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {

Eigen::Isometry3d calibrated_T_BC(const Eigen::Isometry3d& T_BC0, const double* phi) {
  Eigen::Isometry3d T = T_BC0;
  T.linear() = T_BC0.linear() * geometry::so3_exp(Eigen::Map<const Eigen::Vector3d>(phi));
  return T;
}

CameraRotationFactor::CameraRotationFactor(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_Cj,
                                           const Eigen::Isometry3d& T_BC0, double sqrt_information)
    : base_(f_Ca, f_Cj, T_BC0, sqrt_information), R_BC0_(T_BC0.linear()) {}

bool CameraRotationFactor::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> phi(parameters[3]);
  const Eigen::Matrix3d R_BC = R_BC0_ * geometry::so3_exp(phi);
  const bool want_phi = jacobians != nullptr && jacobians[3] != nullptr;
  Eigen::Matrix<double, 2, 3, Eigen::RowMajor> dr_dperturbation;
  if (!base_.evaluate_with(R_BC, parameters, residuals, jacobians, want_phi ? dr_dperturbation.data() : nullptr)) {
    return false;
  }
  // R_BC0 Exp(phi + dphi) = R_BC Exp(Jr(phi) dphi).
  if (want_phi) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>>{jacobians[3]} =
        dr_dperturbation * geometry::so3_right_jacobian(phi);
  }
  return true;
}

std::unique_ptr<ceres::CostFunction> new_camera_rotation_prior(double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("camera rotation prior: sigma must be > 0");
  const ceres::Matrix A = ceres::Matrix::Identity(3, 3) / sigma_rad;
  return std::make_unique<ceres::NormalPrior>(A, ceres::Vector::Zero(3));
}

}  // namespace twinslam::estimator
