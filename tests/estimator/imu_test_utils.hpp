#pragma once
// Ideal (optionally biased and noisy) IMU samples from the analytic trajectory, and the true keyframe states.
#include <cstdint>
#include <random>
#include <vector>

#include "analytic_trajectory.hpp"
#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/imu_types.hpp"

namespace twinslam::testing {

inline const Eigen::Vector3d kGravity_W(0.0, 0.0, -9.81);

inline double seconds(std::int64_t ns) { return 1e-9 * static_cast<double>(ns); }

// Samples at rate_hz from t0_ns to t1_ns inclusive: exact measurements plus a constant bias.
inline std::vector<estimator::ImuSample> simulate_imu(const AnalyticTrajectory& traj, std::int64_t t0_ns,
                                                      std::int64_t t1_ns, double rate_hz,
                                                      const estimator::ImuBias& bias = {}) {
  const auto period_ns = static_cast<std::int64_t>(1e9 / rate_hz);
  std::vector<estimator::ImuSample> out;
  for (std::int64_t t = t0_ns; t <= t1_ns; t += period_ns) {
    const TrajectoryPoint s = traj.at(seconds(t));
    out.push_back({t, s.omega_B + bias.gyro, traj.specific_force_B(seconds(t), kGravity_W) + bias.accel});
  }
  return out;
}

// Adds discrete white noise of continuous densities (per sample sigma_d = density * sqrt(rate)).
inline void add_white_noise(std::vector<estimator::ImuSample>& samples, const estimator::ImuNoise& noise,
                            double rate_hz, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double sg = noise.gyroscope_noise_density * std::sqrt(rate_hz);
  const double sa = noise.accelerometer_noise_density * std::sqrt(rate_hz);
  for (auto& s : samples) {
    for (int k = 0; k < 3; ++k) {
      s.gyro_B[k] += sg * n(rng);
      s.accel_B[k] += sa * n(rng);
    }
  }
}

// True state at time t (W is used as the estimator's L).
inline estimator::ImuState true_state(const AnalyticTrajectory& traj, std::int64_t t_ns,
                                      const estimator::ImuBias& bias = {}) {
  const TrajectoryPoint s = traj.at(seconds(t_ns));
  estimator::ImuState st;
  st.p_L = s.p_W;
  st.q_LB = Eigen::Quaterniond(s.R_WB);
  st.v_L = s.v_W;
  st.bias = bias;
  return st;
}

}  // namespace twinslam::testing
