#pragma once
// Ceres cost function of the IMU preintegration factor between keyframes i and j, with analytic Jacobians.
// Parameter blocks (see imu_state.hpp): pose_i [7], speed_bias_i [9], pose_j [7], speed_bias_j [9].
// Residual: S r, where r is imu_residual() (15) and S the square-root information of the preintegrated covariance
// plus the bias random walk (Preintegration::sqrt_information()).
#include <memory>

#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

#include "twinslam/estimator/imu_residual.hpp"
#include "twinslam/estimator/preintegration.hpp"

namespace twinslam::estimator {

// Gravity in the gravity-aligned local frame L [m/s^2].
inline const Eigen::Vector3d kDefaultGravity_L(0.0, 0.0, -9.81);

class ImuFactor final : public ceres::SizedCostFunction<15, kPoseSize, kSpeedBiasSize, kPoseSize, kSpeedBiasSize> {
 public:
  // The factor reads `preintegration` at every evaluation, so the owner may repropagate it between solves (e.g. via
  // Preintegration::repropagate_if_needed) without rebuilding the problem; it must not change during a solve.
  ImuFactor(std::shared_ptr<const Preintegration> preintegration, const Eigen::Vector3d& g_L = kDefaultGravity_L);

  // Jacobians are w.r.t. the ambient coordinates of each block: for the quaternion, the closed-form derivative w.r.t.
  // the right rotation perturbation times geometry::right_perturbation_jacobian(q), which is exact for any manifold.
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

  const Preintegration& preintegration() const { return *pre_; }

 private:
  std::shared_ptr<const Preintegration> pre_;
  Eigen::Vector3d g_L_;
};

}  // namespace twinslam::estimator
