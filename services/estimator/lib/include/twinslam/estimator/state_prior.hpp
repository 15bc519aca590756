#pragma once
// Gaussian priors on one keyframe's state, used for the initial keyframe: they define the gauge of L (position 0,
// yaw 0) and carry the static initialization's roll/pitch, velocity and bias uncertainty. Once that keyframe is
// marginalized, the information moves into the MarginalizationPrior.
#include <ceres/cost_function.h>

#include "twinslam/estimator/imu_state.hpp"

namespace twinslam::estimator {

struct StatePriorSigmas {
  double position_m = 1e-3;
  double roll_pitch_rad = 0.02;
  double yaw_rad = 1e-3;
  double velocity_mps = 0.05;
  double gyro_bias_radps = 0.01;
  double accel_bias_mps2 = 0.2;
};

// Residual (6): [(p_L - p0) / sigma_p; W Log(q_LB q0^-1)], the rotation error in L so that its z is the yaw error
// and x, y the tilt (2 vec(q) small-angle form), W = diag(1/s_rp, 1/s_rp, 1/s_yaw). Block: pose [7].
ceres::CostFunction* new_pose_prior(const ImuState& prior, const StatePriorSigmas& sigmas);
// Residual (9): whitened [v_L - v0, b_g - bg0, b_a - ba0]. Block: speed_bias [9].
ceres::CostFunction* new_speed_bias_prior(const ImuState& prior, const StatePriorSigmas& sigmas);

// Residual (3): v_L / sigma_mps, the zero-velocity update of a frame at rest. Block: speed_bias [9].
ceres::CostFunction* new_zero_velocity_factor(double sigma_mps);

}  // namespace twinslam::estimator
