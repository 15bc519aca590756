#pragma once
// Simulated IMU (body B = IMU frame): exact specific force and angular rate from the trajectory's analytic
// derivatives, plus the continuous-time noise model of Kalibr/EuRoC discretized at the sample period dt:
//   white noise  n_k ~ N(0, sigma^2 / dt)          (sigma = *_noise density)
//   bias walk    r_{k+1} = r_k + N(0, sigma_w^2 dt)  (sigma_w = *_walk density), starting at zero,
// and the errors of a consumer MEMS part that a datasheet-style calibration (imu0/sensor.yaml) does not state:
//   turn-on bias  o ~ N(0, *_turn_on_bias^2) per axis, fixed for the flight
//   instability   m_{k+1} = phi m_k + N(0, (1 - phi^2) *_bias_instability^2), phi = exp(-dt / bias_tau_s),
//                 m_0 ~ N(0, *_bias_instability^2) (first-order Gauss-Markov, stationary)
//   K = I + diag(s) + C   scale factors s_i ~ N(0, *_scale_error^2), cross-axis couplings C_ij ~ N(0,
//                 *_misalignment^2) (i != j: axis misalignment and non-orthogonality), fixed for the flight
//   gyro_k  = K_g w_B(t_k) + b_g,k + n_g,k,                                   b = o + m + r (the true total bias)
//   accel_k = K_a R_WB(t_k)^T (a_W(t_k) - g_W) + b_a,k + n_a,k,   g_W = (0, 0, -9.81)
// Noise, walk, instability and device errors come from separate random streams of the seed, so turning one off
// (its key 0) leaves the others' draws unchanged; with every error key 0 the samples are those of the ideal model.
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

// The fixed errors of the simulated device (drawn from `seed`; zero / identity for keys that are 0).
struct ImuDeviceErrors {
  Eigen::Matrix3d gyro_matrix = Eigen::Matrix3d::Identity();   // K_g: gyro = K_g w_B + b_g + n_g
  Eigen::Matrix3d accel_matrix = Eigen::Matrix3d::Identity();  // K_a
  Eigen::Vector3d gyro_turn_on_bias = Eigen::Vector3d::Zero();   // [rad/s]
  Eigen::Vector3d accel_turn_on_bias = Eigen::Vector3d::Zero();  // [m/s^2]
};
ImuDeviceErrors imu_device_errors(const ImuSimConfig& config, std::uint64_t seed);

// Noise-free specific force in B [m/s^2] of a trajectory state.
Eigen::Vector3d specific_force_B(const FlightState& state);

// Samples at config.rate_hz over [0, trajectory.duration()] (clock.hpp stamps). Same seed -> identical samples.
std::vector<ImuSample> simulate_imu(const FlightTrajectory& trajectory, const ImuSimConfig& config,
                                    std::uint64_t seed);

}  // namespace twinslam::sim
