// IMU: the noise-free measurements integrate back to the ground truth (so specific force, gravity sign, frames and
// body rates are consistent), the noise has the stated densities, and the same seed gives the same samples.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/imu_sim.hpp"

namespace twinslam::sim {
namespace {

using testing::hints_for;

struct State {
  Eigen::Quaterniond q_WB;
  Eigen::Vector3d v_W, p_W;
};

// Time derivative of the state for body rate w [rad/s] and specific force f [m/s^2] (both in B).
State derivative(const State& x, const Eigen::Vector3d& w, const Eigen::Vector3d& f) {
  State d;
  d.q_WB.coeffs() = (x.q_WB * Eigen::Quaterniond(0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z())).coeffs();
  d.v_W = x.q_WB.normalized() * f + kGravity_W;
  d.p_W = x.v_W;
  return d;
}

State add(const State& x, const State& d, double h) {
  State y;
  y.q_WB.coeffs() = x.q_WB.coeffs() + h * d.q_WB.coeffs();
  y.v_W = x.v_W + h * d.v_W;
  y.p_W = x.p_W + h * d.p_W;
  return y;
}

// Classical RK4 with step 2 dt over samples k (start), k+1 (midpoint), k+2 (end) of the 200 Hz stream.
Eigen::Vector3d integrate(const std::vector<ImuSample>& imu, const FlightState& start, std::size_t steps) {
  State x{Eigen::Quaterniond(start.R_WB), start.v_W, start.p_W};
  for (std::size_t k = 0; k + 2 <= 2 * steps; k += 2) {
    const double h = (imu[k + 2].stamp_ns - imu[k].stamp_ns) * 1e-9;
    const auto& a = imu[k];
    const auto& m = imu[k + 1];
    const auto& b = imu[k + 2];
    const State k1 = derivative(x, a.gyro_radps, a.accel_mps2);
    const State k2 = derivative(add(x, k1, h / 2), m.gyro_radps, m.accel_mps2);
    const State k3 = derivative(add(x, k2, h / 2), m.gyro_radps, m.accel_mps2);
    const State k4 = derivative(add(x, k3, h), b.gyro_radps, b.accel_mps2);
    x.q_WB.coeffs() += h / 6 * (k1.q_WB.coeffs() + 2 * k2.q_WB.coeffs() + 2 * k3.q_WB.coeffs() + k4.q_WB.coeffs());
    x.q_WB.normalize();
    x.v_W += h / 6 * (k1.v_W + 2 * k2.v_W + 2 * k3.v_W + k4.v_W);
    x.p_W += h / 6 * (k1.p_W + 2 * k2.p_W + 2 * k3.p_W + k4.p_W);
  }
  return x.p_W;
}

// The ideal model of the densities alone: the consumer-grade errors (turn-on bias, instability, scale factor,
// misalignment; test_imu_errors.cpp) off.
ImuSimConfig without_device_errors(ImuSimConfig c) {
  c.gyro_turn_on_bias = c.accel_turn_on_bias = c.gyro_bias_instability = c.accel_bias_instability = 0;
  c.gyro_scale_error = c.accel_scale_error = c.gyro_misalignment = c.accel_misalignment = 0;
  return c;
}

ImuSimConfig noise_free() {
  ImuSimConfig c = without_device_errors({});
  c.gyro_noise = c.accel_noise = c.gyro_walk = c.accel_walk = 0;
  return c;
}

TEST(SimImu, AtRestMeasuresGravityUpAndNoRotation) {
  const Scenario sc = builtin_scenario("tiny");
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  const FlightState s = f.at(0);
  // Level and still: the accelerometer reads +9.81 along body z (it measures the ground's push, not gravity).
  EXPECT_TRUE(specific_force_B(s).isApprox(Eigen::Vector3d(0, 0, 9.81), 1e-9));
  EXPECT_LT(s.w_B.norm(), 1e-12);
}

TEST(SimImu, NoiseFreeImuIntegratesToGroundTruthWithin1cmAfter10s) {
  for (const std::string name : {"tiny", "city-loops", "city-survey"}) {
    const Scenario sc = builtin_scenario(name);
    const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
    const std::vector<ImuSample> imu = simulate_imu(f, noise_free(), sc.seed);
    ASSERT_EQ(imu.size(), static_cast<std::size_t>(sc.trajectory.duration_s * 200 + 1));
    const std::size_t steps = 1000;  // 1000 x 10 ms = 10 s
    for (const double start_s : {0.0, 12.0}) {  // from rest (with the start-up zig-zag), and in cruise
      const auto k0 = static_cast<std::size_t>(start_s * 200);
      const std::vector<ImuSample> slice(imu.begin() + static_cast<long>(k0), imu.end());
      const Eigen::Vector3d p = integrate(slice, f.at(start_s), steps);
      const double error = (p - f.at(start_s + 10.0).p_W).norm();
      EXPECT_LT(error, 0.01) << name << " from " << start_s << " s";
      std::printf("%-12s from %4.1f s: |p_imu - p_gt| after 10 s = %.2e m\n", name.c_str(), start_s, error);
    }
  }
}

TEST(SimImu, NoiseAndBiasWalkHaveTheStatedDensities) {
  Scenario sc = builtin_scenario("city-loops");
  sc.imu.gyro_noise = 2e-3;
  sc.imu.accel_noise = 2e-2;
  sc.imu.gyro_walk = 1e-4;
  sc.imu.accel_walk = 1e-3;
  sc.imu = without_device_errors(sc.imu);
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  const std::vector<ImuSample> imu = simulate_imu(f, sc.imu, 42);
  const double dt = 1.0 / sc.imu.rate_hz;
  Eigen::Array3d white_g = Eigen::Array3d::Zero(), white_a = Eigen::Array3d::Zero();
  Eigen::Array3d walk_g = Eigen::Array3d::Zero(), walk_a = Eigen::Array3d::Zero();
  for (std::size_t k = 0; k < imu.size(); ++k) {
    const FlightState s = f.at((imu[k].stamp_ns - imu[0].stamp_ns) * 1e-9);
    white_g += (imu[k].gyro_radps - s.w_B - imu[k].gyro_bias_radps).array().square();
    white_a += (imu[k].accel_mps2 - specific_force_B(s) - imu[k].accel_bias_mps2).array().square();
    if (k > 0) {
      walk_g += (imu[k].gyro_bias_radps - imu[k - 1].gyro_bias_radps).array().square();
      walk_a += (imu[k].accel_bias_mps2 - imu[k - 1].accel_bias_mps2).array().square();
    }
  }
  const double n = static_cast<double>(imu.size());  // 60001 samples: std known to about 0.3 %
  const Eigen::Array3d ratio_wg = (white_g / n).sqrt() / (sc.imu.gyro_noise / std::sqrt(dt));
  const Eigen::Array3d ratio_wa = (white_a / n).sqrt() / (sc.imu.accel_noise / std::sqrt(dt));
  const Eigen::Array3d ratio_bg = (walk_g / (n - 1)).sqrt() / (sc.imu.gyro_walk * std::sqrt(dt));
  const Eigen::Array3d ratio_ba = (walk_a / (n - 1)).sqrt() / (sc.imu.accel_walk * std::sqrt(dt));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(ratio_wg[i], 1.0, 0.05) << "gyro white axis " << i;
    EXPECT_NEAR(ratio_wa[i], 1.0, 0.05) << "accel white axis " << i;
    EXPECT_NEAR(ratio_bg[i], 1.0, 0.05) << "gyro walk axis " << i;
    EXPECT_NEAR(ratio_ba[i], 1.0, 0.05) << "accel walk axis " << i;
  }
  EXPECT_TRUE(imu[0].gyro_bias_radps.isZero());
  EXPECT_GT(imu.back().gyro_bias_radps.norm(), 0);
}

TEST(SimImu, SameSeedSameSamplesOtherSeedOtherNoise) {
  const Scenario sc = builtin_scenario("tiny");
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  const auto a = simulate_imu(f, sc.imu, 7), b = simulate_imu(f, sc.imu, 7), c = simulate_imu(f, sc.imu, 8);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].stamp_ns, b[k].stamp_ns);
    ASSERT_EQ(a[k].gyro_radps, b[k].gyro_radps);
    ASSERT_EQ(a[k].accel_mps2, b[k].accel_mps2);
  }
  EXPECT_NE(a[10].gyro_radps, c[10].gyro_radps);
  EXPECT_EQ(a[1].stamp_ns - a[0].stamp_ns, 5'000'000);  // 200 Hz in integer ns
  EXPECT_EQ(a[0].stamp_ns, kEpochNs);
}

}  // namespace
}  // namespace twinslam::sim
