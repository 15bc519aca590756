#include "twinslam/estimator/state_prior.hpp"

#include <ceres/autodiff_cost_function.h>
#include <Eigen/Geometry>

namespace twinslam::estimator {
namespace {

struct PosePriorResidual {
  Eigen::Vector3d p0;
  Eigen::Quaterniond q0_inv;
  Eigen::Vector3d w_p, w_R;  // whitening weights

  template <class T>
  bool operator()(const T* pose, T* r) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p(pose);
    const Eigen::Map<const Eigen::Quaternion<T>> q(pose + 3);
    // Error rotation in L: q q0^-1; 2 vec(.) ~= Log for small errors (sign fixed so w >= 0).
    Eigen::Quaternion<T> dq = q * q0_inv.cast<T>();
    const T sign = dq.w() < T(0) ? T(-1) : T(1);
    for (int k = 0; k < 3; ++k) {
      r[k] = (p[k] - T(p0[k])) * T(w_p[k]);
      r[3 + k] = T(2) * sign * dq.vec()[k] * T(w_R[k]) / q.norm();
    }
    return true;
  }
};

struct SpeedBiasPriorResidual {
  Eigen::Matrix<double, 9, 1> x0, w;
  template <class T>
  bool operator()(const T* sb, T* r) const {
    for (int k = 0; k < 9; ++k) r[k] = (sb[k] - T(x0[k])) * T(w[k]);
    return true;
  }
};

struct ZeroVelocityResidual {
  double w;
  template <class T>
  bool operator()(const T* sb, T* r) const {
    for (int k = 0; k < 3; ++k) r[k] = sb[k] * T(w);
    return true;
  }
};

}  // namespace

ceres::CostFunction* new_zero_velocity_factor(double sigma_mps) {
  return new ceres::AutoDiffCostFunction<ZeroVelocityResidual, 3, kSpeedBiasSize>(new ZeroVelocityResidual{1.0 / sigma_mps});
}

ceres::CostFunction* new_pose_prior(const ImuState& prior, const StatePriorSigmas& s) {
  auto* f = new PosePriorResidual{prior.p_L, prior.q_LB.normalized().inverse(),
                                  Eigen::Vector3d::Constant(1.0 / s.position_m),
                                  Eigen::Vector3d(1.0 / s.roll_pitch_rad, 1.0 / s.roll_pitch_rad, 1.0 / s.yaw_rad)};
  return new ceres::AutoDiffCostFunction<PosePriorResidual, 6, kPoseSize>(f);
}

ceres::CostFunction* new_speed_bias_prior(const ImuState& prior, const StatePriorSigmas& s) {
  auto* f = new SpeedBiasPriorResidual;
  f->x0 << prior.v_L, prior.bias.gyro, prior.bias.accel;
  f->w << Eigen::Vector3d::Constant(1.0 / s.velocity_mps), Eigen::Vector3d::Constant(1.0 / s.gyro_bias_radps),
      Eigen::Vector3d::Constant(1.0 / s.accel_bias_mps2);
  return new ceres::AutoDiffCostFunction<SpeedBiasPriorResidual, 9, kSpeedBiasSize>(f);
}

}  // namespace twinslam::estimator
