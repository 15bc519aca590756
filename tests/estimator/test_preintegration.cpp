// Preintegration of ideal IMU data: true relative motion, static IMU, bias update vs. repropagation, bad input.
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "imu_test_utils.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/imu_residual.hpp"
#include "twinslam/estimator/preintegration.hpp"
#include "twinslam/geometry/so3.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

constexpr double kRate = 200.0;
constexpr double kDeg = M_PI / 180.0;

est::PreintegrationConfig config(est::ImuIntegration method = est::ImuIntegration::kMidpoint) {
  est::PreintegrationConfig c;
  c.integration = method;
  return c;
}

struct MotionError {
  double position_m, rotation_rad, velocity_mps;
};

// Predicts keyframe j from the true keyframe i and compares it with the true keyframe j.
MotionError relative_motion_error(const ts::AnalyticTrajectory& traj, std::int64_t t_i, std::int64_t t_j,
                                  est::ImuIntegration method, const est::ImuBias& bias = {}) {
  const auto samples = ts::simulate_imu(traj, 0, t_j + 100'000'000, kRate, bias);
  const est::Preintegration pre(config(method), bias, samples, t_i, t_j);
  const est::ImuState pred = est::predict(ts::true_state(traj, t_i, bias), pre, ts::kGravity_W);
  const est::ImuState truth = ts::true_state(traj, t_j, bias);
  return {(pred.p_L - truth.p_L).norm(), pred.q_LB.angularDistance(truth.q_LB), (pred.v_L - truth.v_L).norm()};
}

}  // namespace

TEST(Preintegration, MatchesTrueRelativeMotionOverHalfAndThreeSeconds) {
  const ts::AnalyticTrajectory traj;
  // Keyframe stamps deliberately off the 5 ms IMU grid, so the boundary samples are interpolated.
  const std::int64_t t_i = 1'002'300'000;
  for (const std::int64_t span : {500'000'000LL, 3'000'000'000LL}) {
    const MotionError e = relative_motion_error(traj, t_i, t_i + span + 1'700'000, est::ImuIntegration::kMidpoint);
    EXPECT_LT(e.position_m, 1e-3) << "span " << span;
    EXPECT_LT(e.rotation_rad, 0.01 * kDeg) << "span " << span;
    EXPECT_LT(e.velocity_mps, 1e-3) << "span " << span;
  }
}

TEST(Preintegration, MatchesTrueMotionWithKnownBiasRemoved) {
  const ts::AnalyticTrajectory traj;
  est::ImuBias bias;
  bias.gyro << 0.01, -0.02, 0.015;
  bias.accel << 0.2, -0.1, 0.3;
  const MotionError e = relative_motion_error(traj, 2'000'000'000, 5'000'000'000, est::ImuIntegration::kMidpoint, bias);
  EXPECT_LT(e.position_m, 1e-3);
  EXPECT_LT(e.rotation_rad, 0.01 * kDeg);
}

TEST(Preintegration, MidpointIsMoreAccurateThanEuler) {
  // Why midpoint is the default: Euler's first-order error over 3 s is centimetres, midpoint's is far below 1 mm.
  const ts::AnalyticTrajectory traj;
  const MotionError mid = relative_motion_error(traj, 1'000'000'000, 4'000'000'000, est::ImuIntegration::kMidpoint);
  const MotionError euler = relative_motion_error(traj, 1'000'000'000, 4'000'000'000, est::ImuIntegration::kEuler);
  EXPECT_LT(euler.position_m, 0.1);  // still a sane integrator
  EXPECT_LT(20.0 * mid.position_m, euler.position_m);
  EXPECT_LT(20.0 * mid.velocity_mps, euler.velocity_mps);
}

TEST(Preintegration, StaticImuIntegratesToNoMotion) {
  // At rest the accelerometer reads -R_LB^T g and the gyro zero; with gravity added back the state must not move.
  const Eigen::Matrix3d R_LB = tg::so3_exp(Eigen::Vector3d(0.3, -0.2, 1.4));
  std::vector<est::ImuSample> samples;
  for (std::int64_t t = 0; t <= 3'000'000'000; t += 5'000'000) {
    samples.push_back({t, Eigen::Vector3d::Zero(), -R_LB.transpose() * ts::kGravity_W});
  }
  for (auto method : {est::ImuIntegration::kMidpoint, est::ImuIntegration::kEuler}) {
    const est::Preintegration pre(config(method), {}, samples, 123'456'789, 2'987'654'321);
    est::ImuState s_i;
    s_i.p_L << 4.0, -2.0, 1.5;
    s_i.q_LB = Eigen::Quaterniond(R_LB);
    const est::ImuState s_j = est::predict(s_i, pre, ts::kGravity_W);
    EXPECT_LT((s_j.p_L - s_i.p_L).norm(), 1e-9);
    EXPECT_LT(s_j.v_L.norm(), 1e-9);
    EXPECT_LT(s_j.q_LB.angularDistance(s_i.q_LB), 1e-12);
    EXPECT_LT((pre.delta().R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(pre.dt(), 2.864197532, 1e-12);
  }
}

namespace {

struct DeltaError {
  double R, v, p;
};
DeltaError delta_error(const est::PreintegratedDelta& a, const est::PreintegratedDelta& b) {
  return {tg::so3_angle_between(a.R, b.R), (a.v - b.v).norm(), (a.p - b.p).norm()};
}

}  // namespace

TEST(Preintegration, FirstOrderBiasUpdateAgreesWithRepropagationToFirstOrder) {
  const ts::AnalyticTrajectory traj;
  const auto samples = ts::simulate_imu(traj, 0, 4'000'000'000, kRate);
  est::ImuBias step;
  step.gyro << 0.004, -0.003, 0.005;
  step.accel << 0.05, -0.04, 0.03;
  for (auto method : {est::ImuIntegration::kMidpoint, est::ImuIntegration::kEuler}) {
    const est::Preintegration pre(config(method), {}, samples, 500'000'000, 3'500'000'000);
    DeltaError err[2];
    for (int k = 0; k < 2; ++k) {
      const double s = k == 0 ? 1.0 : 0.5;
      est::ImuBias b;
      b.gyro = s * step.gyro;
      b.accel = s * step.accel;
      const est::Preintegration fresh(config(method), b, samples, 500'000'000, 3'500'000'000);
      err[k] = delta_error(pre.corrected(b), fresh.delta());
      if (k == 0) {
        // The update removes almost all of the change a bias causes.
        const DeltaError uncorrected = delta_error(pre.delta(), fresh.delta());
        EXPECT_LT(err[0].R, 0.01 * uncorrected.R);
        EXPECT_LT(err[0].v, 0.01 * uncorrected.v);
        EXPECT_LT(err[0].p, 0.01 * uncorrected.p);
      }
    }
    // What is left is second order: halving the bias change quarters it.
    EXPECT_NEAR(err[1].R / err[0].R, 0.25, 0.03);
    EXPECT_NEAR(err[1].v / err[0].v, 0.25, 0.03);
    EXPECT_NEAR(err[1].p / err[0].p, 0.25, 0.03);
  }
}

TEST(Preintegration, RepropagatesOnlyBeyondTheThresholds) {
  const ts::AnalyticTrajectory traj;
  const auto samples = ts::simulate_imu(traj, 0, 2'000'000'000, kRate);
  est::Preintegration pre(config(), {}, samples, 100'000'000, 1'100'000'000);
  const est::PreintegratedDelta before = pre.delta();

  est::ImuBias small;
  small.gyro << 0.005, 0.0, 0.0;  // below the 0.01 rad/s default
  small.accel << 0.0, 0.05, 0.0;  // below the 0.1 m/s^2 default
  EXPECT_FALSE(pre.repropagate_if_needed(small));
  EXPECT_EQ(pre.linearization_bias().gyro, Eigen::Vector3d::Zero());
  EXPECT_EQ(pre.delta().v, before.v);

  est::ImuBias large = small;
  large.accel.y() = 0.2;
  EXPECT_TRUE(pre.repropagate_if_needed(large));
  EXPECT_EQ(pre.linearization_bias().accel, large.accel);
  const est::Preintegration fresh(config(), large, samples, 100'000'000, 1'100'000'000);
  EXPECT_LT(delta_error(pre.delta(), fresh.delta()).p, 1e-15);
  EXPECT_LT((pre.bias_jacobians().dp_dbg - fresh.bias_jacobians().dp_dbg).norm(), 1e-15);
  EXPECT_LT((pre.covariance() - fresh.covariance()).norm(), 1e-20);
}

TEST(Preintegration, NodesInterpolateTheBoundarySamples) {
  std::vector<est::ImuSample> samples;
  for (std::int64_t t = 0; t <= 100'000'000; t += 10'000'000) {
    samples.push_back({t, Eigen::Vector3d(1e-9 * t, 0, 0), Eigen::Vector3d(0, 0, 2.0 * 1e-9 * t)});
  }
  const est::Preintegration pre(config(), {}, samples, 25'000'000, 70'000'000);
  const auto& nodes = pre.nodes();
  ASSERT_EQ(nodes.size(), 6u);  // 25 ms (interpolated), 30, 40, 50, 60 ms, 70 ms (on a sample)
  EXPECT_EQ(nodes.front().stamp_ns, 25'000'000);
  EXPECT_NEAR(nodes.front().gyro_B.x(), 0.025, 1e-15);
  EXPECT_NEAR(nodes.front().accel_B.z(), 0.05, 1e-15);
  EXPECT_EQ(nodes.back().stamp_ns, 70'000'000);
  EXPECT_NEAR(nodes.back().gyro_B.x(), 0.07, 1e-15);
}

namespace {

std::string input_error_of(const std::vector<est::ImuSample>& samples, std::int64_t t_i, std::int64_t t_j,
                           est::PreintegrationConfig c = config()) {
  try {
    est::Preintegration pre(c, {}, samples, t_i, t_j);
  } catch (const twinslam::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Preintegration, RejectsBadInputWithAReason) {
  std::vector<est::ImuSample> good;
  for (std::int64_t t = 0; t <= 50'000'000; t += 5'000'000) {
    good.push_back({t, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.81)});
  }

  auto backwards = good;
  std::swap(backwards[3], backwards[4]);
  EXPECT_NE(input_error_of(backwards, 0, 40'000'000).find("do not increase"), std::string::npos);

  auto nan = good;
  nan[2].accel_B.y() = std::nan("");
  EXPECT_NE(input_error_of(nan, 0, 40'000'000).find("not finite"), std::string::npos);

  EXPECT_NE(input_error_of(good, 0, 60'000'000).find("do not cover"), std::string::npos);
  EXPECT_NE(input_error_of(good, 30'000'000, 30'000'000).find("must increase"), std::string::npos);

  auto c = config();
  c.noise.accelerometer_noise_density = 0.0;
  EXPECT_NE(input_error_of(good, 0, 40'000'000, c).find("accelerometer_noise_density"), std::string::npos);
}

TEST(Preintegration, CoveringSamplesSelectsTheBracketingSlice) {
  std::vector<est::ImuSample> buffer;
  for (std::int64_t t = 0; t <= 100; t += 10) buffer.push_back({t, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  auto slice = est::covering_samples(buffer, 25, 60);  // 20 (before 25) .. 60 (exactly t_j)
  ASSERT_EQ(slice.size(), 5u);
  EXPECT_EQ(slice.front().stamp_ns, 20);
  EXPECT_EQ(slice.back().stamp_ns, 60);
  slice = est::covering_samples(buffer, 30, 61);  // 30 (exactly t_i) .. 70 (after 61)
  EXPECT_EQ(slice.front().stamp_ns, 30);
  EXPECT_EQ(slice.back().stamp_ns, 70);
  // Beyond the buffer the slice is clipped and the constructor reports the gap.
  slice = est::covering_samples(buffer, 90, 130);
  EXPECT_EQ(slice.front().stamp_ns, 90);
  EXPECT_EQ(slice.back().stamp_ns, 100);
  EXPECT_THROW(est::Preintegration(est::PreintegrationConfig{}, {}, slice, 90, 130), twinslam::InputError);
}

// Issue 15: a gap in the IMU stream. The motion inside it was not measured, so the preintegrated covariance must
// grow by what an unknown constant rate and acceleration of the gap sigmas do over it (rotation sigma_g dt, velocity
// sigma_a dt, position sigma_a dt^2 / 2), while the same samples without the gap keep the sensor's own tiny noise.
TEST(Preintegration, AnImuGapAddsTheUnmeasuredMotionsCovariance) {
  std::vector<est::ImuSample> samples;
  for (std::int64_t t = 0; t <= 3'000'000'000; t += 5'000'000) {
    if (t > 1'000'000'000 && t < 2'000'000'000) continue;  // 1 s without samples
    samples.push_back({t, Eigen::Vector3d(0.01, -0.02, 0.1), Eigen::Vector3d(0.2, 0.1, 9.81)});
  }
  est::PreintegrationConfig c = config();
  const est::Preintegration gap(c, {}, samples, 0, 3'000'000'000);
  EXPECT_NEAR(gap.longest_gap_s(), 1.0, 1e-9);
  c.gap_s = 2.0;  // the same samples with the gap not recognised
  const est::Preintegration blind(c, {}, samples, 0, 3'000'000'000);
  EXPECT_NEAR(blind.longest_gap_s(), 1.0, 1e-9);
  const Eigen::Matrix<double, 9, 1> var_gap = gap.covariance().diagonal(), var_blind = blind.covariance().diagonal();
  const double dt = 1.0;
  for (int k = 0; k < 3; ++k) {
    // Lower bounds: rotation and velocity are rotated by at most 0.3 rad over the interval, so per axis at least
    // half the gap's variance stays on the axis.
    EXPECT_GT(var_gap(k), 0.5 * std::pow(c.gap_gyro_sigma * dt, 2)) << "rotation axis " << k;
    EXPECT_GT(var_gap(3 + k), 0.5 * std::pow(c.gap_accel_sigma * dt, 2)) << "velocity axis " << k;
    EXPECT_GT(var_gap(6 + k), 0.5 * std::pow(c.gap_accel_sigma * dt * dt / 2, 2)) << "position axis " << k;
    EXPECT_LT(var_blind(3 + k), 1e-3) << "velocity axis " << k;
  }
  // Still a covariance: symmetric and positive definite, so the IMU factor can whiten with it.
  EXPECT_LT((gap.covariance() - gap.covariance().transpose()).norm(), 1e-12);
  const Eigen::SelfAdjointEigenSolver<est::Preintegration::Matrix9d> eig(gap.covariance());
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  // The prediction itself does not change: only the weight.
  EXPECT_LT((gap.delta().p - blind.delta().p).norm(), 1e-12);
}
