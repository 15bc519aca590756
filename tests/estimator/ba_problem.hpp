#pragma once
// A small visual-inertial bundle adjustment for tests and benchmarks: keyframes along the analytic trajectory, a
// forward camera, landmarks as anchored inverse depth, ideal bearings, and IMU preintegration between keyframes.
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <ceres/ceres.h>

#include "imu_test_utils.hpp"
#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "vision_test_utils.hpp"

namespace twinslam::testing {

struct BaObservation {
  int keyframe = 0;
  Eigen::Vector3d f_C;  // unit bearing in that keyframe's camera
};

struct BaLandmark {
  int anchor = 0;
  Eigen::Vector3d f_Ca;                   // anchor bearing (the anchor's observation)
  double rho = 0.0;                       // true inverse depth [1/m]
  Eigen::Vector3d p_L;                    // true position [m]
  std::vector<BaObservation> observations;  // the other keyframes that see it
};

struct BaProblem {
  Eigen::Isometry3d T_BC = forward_camera_T_BC();
  estimator::ImuBias bias;                  // true, constant
  std::vector<std::int64_t> stamps_ns;
  std::vector<estimator::ImuState> truth;   // per keyframe (W of the trajectory used as L)
  std::vector<std::shared_ptr<estimator::Preintegration>> imu;  // imu[k]: keyframe k -> k + 1
  std::vector<BaLandmark> landmarks;
};

// Keyframes every 0.5 s from t = 0.5 s (about 0.5-1 m apart), landmarks 4-15 m in front of their anchor within 30 deg
// of its optical axis, kept if at least two other keyframes see them within 60 deg of their axes.
inline BaProblem make_ba_problem(int keyframes = 5, int landmarks = 50, unsigned seed = 1) {
  BaProblem p;
  p.bias.gyro << 0.004, -0.006, 0.002;
  p.bias.accel << 0.08, -0.05, 0.12;
  const AnalyticTrajectory traj;
  for (int k = 0; k < keyframes; ++k) {
    p.stamps_ns.push_back(500'000'000 + 500'000'000LL * k);
    p.truth.push_back(true_state(traj, p.stamps_ns.back(), p.bias));
  }
  const auto samples = simulate_imu(traj, 0, p.stamps_ns.back() + 100'000'000, 200.0, p.bias);
  for (int k = 0; k + 1 < keyframes; ++k) {
    // Linearized at the true bias: noise-free data is then consistent to the discretization error (~1e-6).
    p.imu.push_back(std::make_shared<estimator::Preintegration>(estimator::PreintegrationConfig{}, p.bias, samples,
                                                                p.stamps_ns[k], p.stamps_ns[k + 1]));
  }
  std::vector<Eigen::Isometry3d> T_LC;
  for (const auto& s : p.truth) T_LC.push_back(geometry::make_pose(s.q_LB, s.p_L) * p.T_BC);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double kPi = 3.14159265358979323846;
  while (static_cast<int>(p.landmarks.size()) < landmarks) {
    BaLandmark lm;
    lm.anchor = static_cast<int>(u(rng) * keyframes) % keyframes;
    const double polar = 30.0 * kPi / 180.0 * std::sqrt(u(rng)), azimuth = 2 * kPi * u(rng);
    lm.f_Ca = Eigen::Vector3d(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
    lm.rho = 1.0 / (4.0 + 11.0 * u(rng));
    lm.p_L = T_LC[lm.anchor] * (lm.f_Ca / lm.rho);
    for (int k = 0; k < keyframes; ++k) {
      const Eigen::Vector3d p_C = T_LC[k].inverse() * lm.p_L;
      if (k != lm.anchor && p_C.z() > p_C.norm() * std::cos(60.0 * kPi / 180.0)) {
        lm.observations.push_back({k, p_C.normalized()});
      }
    }
    if (lm.observations.size() >= 2) p.landmarks.push_back(lm);
  }
  return p;
}

// The variables as Ceres parameter blocks (layouts of imu_state.hpp and landmark.hpp).
struct BaState {
  std::vector<std::array<double, 7>> pose;
  std::vector<std::array<double, 9>> speed_bias;
  std::vector<double> rho;
};

inline BaState true_ba_state(const BaProblem& p) {
  BaState s;
  for (const auto& t : p.truth) {
    s.pose.emplace_back();
    s.speed_bias.emplace_back();
    estimator::pack(t, s.pose.back().data(), s.speed_bias.back().data());
  }
  for (const auto& lm : p.landmarks) s.rho.push_back(lm.rho);
  return s;
}

// Every keyframe but the first (the gauge) moved by ~5 cm per axis and ~1 deg, velocities by ~0.1 m/s, biases reset
// to zero, inverse depths scaled by up to +-20 %.
inline BaState perturbed_ba_state(const BaProblem& p, std::mt19937& rng) {
  BaState s = true_ba_state(p);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t k = 1; k < s.pose.size(); ++k) {
    double* pose = s.pose[k].data();
    Eigen::Map<Eigen::Vector3d>{pose} += random_vector(rng, 0.05);
    Eigen::Map<Eigen::Vector4d>{pose + 3} =
        (Eigen::Map<Eigen::Quaterniond>(pose + 3) * geometry::quaternion_exp(random_vector(rng, 0.017))).coeffs();
  }
  for (auto& sb : s.speed_bias) {
    Eigen::Map<Eigen::Vector3d>{sb.data()} += random_vector(rng, 0.1);
    std::fill(sb.begin() + 3, sb.end(), 0.0);
  }
  for (double& rho : s.rho) rho *= 1.0 + 0.2 * u(rng);
  return s;
}

// Adds the IMU factors, one ReprojectionFactor per non-anchor observation (with the recommended loss), and the pose
// manifolds; keyframe 0's pose is held constant (gauge) when fix_first_pose. `bearings` may replace the ideal
// observations (same order as BaLandmark::observations).
inline void add_ba_to_problem(const BaProblem& p, BaState& s, ceres::Problem& problem,
                              const estimator::ReprojectionNoise& noise = {}, bool fix_first_pose = true) {
  for (std::size_t k = 0; k + 1 < s.pose.size(); ++k) {
    problem.AddResidualBlock(new estimator::ImuFactor(p.imu[k], kGravity_W), nullptr, s.pose[k].data(),
                             s.speed_bias[k].data(), s.pose[k + 1].data(), s.speed_bias[k + 1].data());
  }
  for (std::size_t i = 0; i < p.landmarks.size(); ++i) {
    const BaLandmark& lm = p.landmarks[i];
    for (const auto& o : lm.observations) {
      problem.AddResidualBlock(
          new estimator::ReprojectionFactor(lm.f_Ca, o.f_C, p.T_BC, noise.sqrt_information()),
          estimator::new_reprojection_loss(noise), s.pose[lm.anchor].data(), s.pose[o.keyframe].data(), &s.rho[i]);
    }
  }
  for (auto& pose : s.pose) problem.SetManifold(pose.data(), estimator::new_pose_manifold());
  if (fix_first_pose) problem.SetParameterBlockConstant(s.pose[0].data());
}

}  // namespace twinslam::testing
