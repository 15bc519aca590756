#pragma once
// Simulated input of the sliding-window estimator: the analytic trajectory, noisy biased IMU at 200 Hz, a cloud of
// landmarks around the flight seen by the forward camera as unit bearings with pixel noise, at 20 Hz.
#include <cmath>
#include <random>
#include <vector>

#include "imu_test_utils.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "vision_test_utils.hpp"

namespace twinslam::testing {

struct SimFrame {
  std::int64_t stamp_ns = 0;
  std::vector<estimator::FeatureBearing> features;
  estimator::ImuState truth;
};

struct SimRun {
  estimator::ImuBias bias;
  std::vector<estimator::ImuSample> imu;
  std::vector<SimFrame> frames;
  Eigen::Isometry3d T_BC = forward_camera_T_BC();
  std::vector<Eigen::Vector3d> points;  // p_W of landmark i (feature id i) [m]
};

// Bearing f plus isotropic tangent-plane noise of `sigma_rad`, renormalized.
inline Eigen::Vector3d noisy_bearing(const Eigen::Vector3d& f, double sigma_rad, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, sigma_rad);
  Eigen::Vector3d d(n(rng), n(rng), n(rng));
  d -= f * f.dot(d);
  return (f + d).normalized();
}

// The landmark cloud: `inner_m` to `outer_m` from the middle of the flight (the trajectory must stay inside), seen within
// 45 deg of the optical axis and up to `range_m`.
struct LandmarkShell {
  double inner_m = 15.0, outer_m = 30.0, range_m = 40.0;
};

// duration_s of flight in `traj` with noisy biased IMU and noisy bearings of `landmarks` points in `shell`.
inline SimRun make_sim_run(double duration_s, double pixel_sigma, unsigned seed, int landmarks = 2000,
                           double focal_px = 460.0, const AnalyticTrajectory& traj = {},
                           const LandmarkShell& shell = {}) {
  SimRun run;
  run.bias.gyro << 0.003, -0.002, 0.001;
  run.bias.accel << 0.05, -0.04, 0.06;
  const auto t_end = static_cast<std::int64_t>(duration_s * 1e9);
  run.imu = simulate_imu(traj, 0, t_end + 200'000'000, 200.0, run.bias);
  std::mt19937 rng(seed);
  add_white_noise(run.imu, estimator::ImuNoise{}, 200.0, rng);

  std::vector<Eigen::Vector3d>& points = run.points;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d centre = traj.at(duration_s / 2).p_W;
  while (static_cast<int>(points.size()) < landmarks) {
    const Eigen::Vector3d d(u(rng), u(rng), 0.5 * u(rng));
    if (d.norm() < 0.1 || d.norm() > 1.0) continue;
    points.push_back(centre + d.normalized() * (shell.inner_m + (shell.outer_m - shell.inner_m) * (0.5 + 0.5 * u(rng))));
  }
  const double cos_fov = std::cos(45.0 * 3.14159265358979 / 180.0);
  for (std::int64_t t = 100'000'000; t <= t_end; t += 50'000'000) {
    SimFrame f;
    f.stamp_ns = t;
    f.truth = true_state(traj, t, run.bias);
    const Eigen::Isometry3d T_LC = geometry::make_pose(f.truth.q_LB, f.truth.p_L) * run.T_BC;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p_C = T_LC.inverse() * points[i];
      if (p_C.norm() > shell.range_m || p_C.z() < p_C.norm() * cos_fov) continue;
      f.features.push_back({static_cast<std::int64_t>(i), noisy_bearing(p_C.normalized(), pixel_sigma / focal_px, rng)});
    }
    run.frames.push_back(std::move(f));
  }
  return run;
}

}  // namespace twinslam::testing
