#include "twinslam/estimator/lens_calibration.hpp"

#include <cmath>
#include <stdexcept>

#include <ceres/manifold.h>
#include <ceres/normal_prior.h>

namespace twinslam::estimator {
namespace {

// sin(t)/t and (d/dt (sin(t)/t)) / t, with their series near 0 (the optical axis).
double sinc(double t) { return std::abs(t) < 1e-4 ? 1.0 - t * t / 6.0 : std::sin(t) / t; }
double sinc_slope_over_t(double t) {
  return std::abs(t) < 1e-3 ? -1.0 / 3.0 + t * t / 30.0 : (t * std::cos(t) - std::sin(t)) / (t * t * t);
}

}  // namespace

Eigen::Vector3d corrected_bearing(const Eigen::Vector3d& f_in, const double* c,
                                  Eigen::Matrix<double, 3, kLensSize>* dfc_dc) {
  const Eigen::Vector3d f = f_in.normalized();
  const double r_xy = f.head<2>().norm();
  const double theta = std::atan2(r_xy, f.z());
  // q = theta u; on the axis u is undefined and q = 0.
  const Eigen::Vector2d q = r_xy > 1e-12 ? Eigen::Vector2d(f.head<2>() * (theta / r_xy)) : Eigen::Vector2d::Zero();
  const double gain = 1.0 + c[0] + c[1] * theta * theta;
  const Eigen::Vector2d qc = gain * q + Eigen::Vector2d(c[2], c[3]);
  const double t = qc.norm();
  Eigen::Vector3d out;
  out.head<2>() = sinc(t) * qc;
  out.z() = std::cos(t);
  if (dfc_dc != nullptr) {
    Eigen::Matrix<double, 3, 2> df_dqc;
    df_dqc.topRows<2>() = sinc(t) * Eigen::Matrix2d::Identity() + sinc_slope_over_t(t) * qc * qc.transpose();
    df_dqc.row(2) = -sinc(t) * qc.transpose();
    Eigen::Matrix<double, 2, kLensSize> dqc_dc;
    dqc_dc.col(0) = q;
    dqc_dc.col(1) = theta * theta * q;
    dqc_dc.rightCols<2>().setIdentity();
    *dfc_dc = df_dqc * dqc_dc;
  }
  return out;
}

LensCalibrationFactor::LensCalibrationFactor(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_Cj,
                                             const Eigen::Isometry3d& T_BC, double sqrt_information)
    : base_(f_Ca, f_Cj, T_BC, sqrt_information), T_BC_(T_BC), sqrt_information_(sqrt_information) {}

bool LensCalibrationFactor::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const double* c = parameters[3];
  const bool want_c = jacobians != nullptr && jacobians[3] != nullptr;
  Eigen::Matrix<double, 3, kLensSize> dfa_dc, dfo_dc;
  const Eigen::Vector3d f_a = corrected_bearing(base_.anchor_bearing(), c, want_c ? &dfa_dc : nullptr);
  const Eigen::Vector3d f_o = corrected_bearing(base_.observed_bearing(), c, want_c ? &dfo_dc : nullptr);
  Eigen::Matrix<double, 2, 3, Eigen::RowMajor> dr_dfa, dr_dfo;
  if (!base_.evaluate_bearings(f_a, f_o, parameters, residuals, jacobians, want_c ? dr_dfa.data() : nullptr,
                               want_c ? dr_dfo.data() : nullptr)) {
    return false;
  }
  if (want_c) {
    Eigen::Map<Eigen::Matrix<double, 2, kLensSize, Eigen::RowMajor>>{jacobians[3]} = dr_dfa * dfa_dc + dr_dfo * dfo_dc;
  }
  return true;
}

ReprojectionFactor LensCalibrationFactor::corrected(const double* c) const {
  return ReprojectionFactor(corrected_bearing(base_.anchor_bearing(), c),
                            corrected_bearing(base_.observed_bearing(), c), T_BC_, sqrt_information_);
}

double LensCalibrationFactor::angular_error(const double* pose_a, const double* pose_j, double rho,
                                            const double* c) const {
  return corrected(c).angular_error(pose_a, pose_j, rho);
}

bool LensCalibrationFactor::in_front(const double* pose_a, const double* pose_j, double rho, const double* c) const {
  return corrected(c).in_front(pose_a, pose_j, rho);
}

std::unique_ptr<ceres::CostFunction> new_lens_prior(const std::array<double, kLensSize>& sigmas) {
  const std::vector<int> free = free_lens_components(sigmas);
  if (free.empty()) throw std::invalid_argument("lens prior: no sigma > 0");
  ceres::Matrix A = ceres::Matrix::Zero(static_cast<int>(free.size()), kLensSize);
  for (std::size_t row = 0; row < free.size(); ++row) A(row, free[row]) = 1.0 / sigmas[free[row]];
  return std::make_unique<ceres::NormalPrior>(A, ceres::Vector::Zero(kLensSize));
}

std::vector<int> free_lens_components(const std::array<double, kLensSize>& sigmas) {
  std::vector<int> free;
  for (int k = 0; k < kLensSize; ++k) {
    if (sigmas[k] > 0.0) free.push_back(k);
  }
  return free;
}

std::unique_ptr<ceres::Manifold> new_lens_manifold(const std::array<double, kLensSize>& sigmas) {
  std::vector<int> fixed;
  for (int k = 0; k < kLensSize; ++k) {
    if (!(sigmas[k] > 0.0)) fixed.push_back(k);
  }
  if (fixed.empty()) return nullptr;
  return std::make_unique<ceres::SubsetManifold>(kLensSize, fixed);
}

}  // namespace twinslam::estimator
