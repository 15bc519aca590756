#pragma once
// Simulated IMU (body B = IMU frame): exact specific force and angular rate from the trajectory's analytic
// derivatives, plus the continuous-time noise model of Kalibr/EuRoC discretized at the sample period dt:
//   white noise  n_k ~ N(0, sigma^2 / dt)          (sigma = *_noise density)
//   bias         b_{k+1} = b_k + N(0, sigma_w^2 dt)  (sigma_w = *_walk density), starting at zero.
//   gyro_k  = w_B(t_k) + b_g,k + n_g,k
//   accel_k = R_WB(t_k)^T (a_W(t_k) - g_W) + b_a,k + n_a,k,   g_W = (0, 0, -9.81)
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/flight_trajectory.hpp"

namespace twinslam::sim {

struct ImuSample {
  std::int64_t stamp_ns = 0;
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();      // measured w_B [rad/s]
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();      // measured specific force in B [m/s^2]
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();  // true bias contained in gyro_radps
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();  // true bias contained in accel_mps2
};

// Noise-free specific force in B [m/s^2] of a trajectory state.
Eigen::Vector3d specific_force_B(const FlightState& state);

// Samples at config.rate_hz over [0, trajectory.duration()] (clock.hpp stamps). Same seed -> identical samples.
std::vector<ImuSample> simulate_imu(const FlightTrajectory& trajectory, const ImuSimConfig& config,
                                    std::uint64_t seed);

}  // namespace twinslam::sim
