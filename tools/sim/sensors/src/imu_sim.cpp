#include "twinslam/sim/imu_sim.hpp"

#include <cmath>
#include <random>

#include "seeds.hpp"
#include "twinslam/sim/clock.hpp"

namespace twinslam::sim {

Eigen::Vector3d specific_force_B(const FlightState& s) { return s.R_WB.transpose() * (s.a_W - kGravity_W); }

std::vector<ImuSample> simulate_imu(const FlightTrajectory& trajectory, const ImuSimConfig& config,
                                    std::uint64_t seed) {
  std::mt19937_64 rng = detail::make_rng(seed, detail::Stream::Imu);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gaussian3 = [&](double sigma) {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = sigma * normal(rng);  // fixed draw order: reproducible
    return v;
  };
  const double dt = 1.0 / config.rate_hz;  // [s]
  const double gyro_white = config.gyro_noise / std::sqrt(dt), accel_white = config.accel_noise / std::sqrt(dt);
  const double gyro_step = config.gyro_walk * std::sqrt(dt), accel_step = config.accel_walk * std::sqrt(dt);

  std::vector<ImuSample> out;
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero(), b_a = Eigen::Vector3d::Zero();
  for (const std::int64_t stamp : sample_stamps(config.rate_hz, trajectory.duration())) {
    const FlightState s = trajectory.at(time_s(stamp));
    ImuSample m;
    m.stamp_ns = stamp;
    m.gyro_bias_radps = b_g;
    m.accel_bias_mps2 = b_a;
    m.gyro_radps = s.w_B + b_g + gaussian3(gyro_white);
    m.accel_mps2 = specific_force_B(s) + b_a + gaussian3(accel_white);
    out.push_back(m);
    b_g += gaussian3(gyro_step);
    b_a += gaussian3(accel_step);
  }
  return out;
}

}  // namespace twinslam::sim
