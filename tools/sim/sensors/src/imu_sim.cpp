#include "twinslam/sim/imu_sim.hpp"

#include <cmath>
#include <random>

#include "seeds.hpp"
#include "twinslam/sim/clock.hpp"

namespace twinslam::sim {

namespace {

// Unit normal draws in a fixed order, scaled afterwards: a key set to 0 changes no other draw.
struct UnitNormals {
  explicit UnitNormals(std::mt19937_64 rng) : rng_(std::move(rng)) {}
  Eigen::Vector3d vec3(double sigma) {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = normal_(rng_);
    return sigma * v;
  }
  // I + diag(scale) + off-diagonal coupling.
  Eigen::Matrix3d matrix(double scale_sigma, double coupling_sigma) {
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i) K(i, i) += scale_sigma * normal_(rng_);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i != j) K(i, j) = coupling_sigma * normal_(rng_);
    return K;
  }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace

Eigen::Vector3d specific_force_B(const FlightState& s) { return s.R_WB.transpose() * (s.a_W - kGravity_W); }

ImuDeviceErrors imu_device_errors(const ImuSimConfig& config, std::uint64_t seed) {
  UnitNormals draw(detail::make_rng(seed, detail::Stream::ImuDevice));
  ImuDeviceErrors e;
  e.gyro_turn_on_bias = draw.vec3(config.gyro_turn_on_bias);
  e.accel_turn_on_bias = draw.vec3(config.accel_turn_on_bias);
  e.gyro_matrix = draw.matrix(config.gyro_scale_error, config.gyro_misalignment);
  e.accel_matrix = draw.matrix(config.accel_scale_error, config.accel_misalignment);
  return e;
}

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

  const ImuDeviceErrors device = imu_device_errors(config, seed);
  // Gauss-Markov bias instability: off when its sigma or its correlation time is 0.
  const bool gauss_markov =
      config.bias_tau_s > 0 && (config.gyro_bias_instability > 0 || config.accel_bias_instability > 0);
  const double phi = gauss_markov ? std::exp(-dt / config.bias_tau_s) : 0.0;
  const double drive = std::sqrt(1.0 - phi * phi);
  UnitNormals instability(detail::make_rng(seed, detail::Stream::ImuInstability));
  Eigen::Vector3d m_g = Eigen::Vector3d::Zero(), m_a = Eigen::Vector3d::Zero();
  if (gauss_markov) {
    m_g = instability.vec3(config.gyro_bias_instability);
    m_a = instability.vec3(config.accel_bias_instability);
  }

  std::vector<ImuSample> out;
  Eigen::Vector3d r_g = Eigen::Vector3d::Zero(), r_a = Eigen::Vector3d::Zero();  // random walks
  for (const std::int64_t stamp : sample_stamps(config.rate_hz, trajectory.duration())) {
    const FlightState s = trajectory.at(time_s(stamp));
    ImuSample m;
    m.stamp_ns = stamp;
    m.gyro_bias_radps = device.gyro_turn_on_bias + m_g + r_g;
    m.accel_bias_mps2 = device.accel_turn_on_bias + m_a + r_a;
    m.gyro_radps = device.gyro_matrix * s.w_B + m.gyro_bias_radps + gaussian3(gyro_white);
    m.accel_mps2 = device.accel_matrix * specific_force_B(s) + m.accel_bias_mps2 + gaussian3(accel_white);
    out.push_back(m);
    r_g += gaussian3(gyro_step);
    r_a += gaussian3(accel_step);
    if (gauss_markov) {
      m_g = phi * m_g + instability.vec3(drive * config.gyro_bias_instability);
      m_a = phi * m_a + instability.vec3(drive * config.accel_bias_instability);
    }
  }
  return out;
}

}  // namespace twinslam::sim
