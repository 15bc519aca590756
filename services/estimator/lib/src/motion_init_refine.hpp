#pragma once
// Maximum-likelihood refinement of the closed-form motion initialization (internal to motion_init.cpp).
// The closed form minimizes distances of landmarks to rays whose directions are themselves noisy (errors in
// variables), which biases the scale toward zero, and it ignores the IMU biases: on simulated flights with 0.5 px
// noise and biases of 0.003 rad/s and 0.05 m/s^2 its velocities came out 20-40 % short and gravity 1-3 deg off.
// Minimizing the angular error of every ray over v_0, g on the sphere |g| = G, both IMU biases (first order through
// the preintegration Jacobians, with priors) and the landmarks removes both errors (a small bundle adjustment).
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace twinslam::estimator {

// What the IMU says about frame k relative to the oldest frame 0 (one preintegration 0 -> k, zero linearization bias).
struct RefineFrame {
  double t_s = 0.0;                                      // t_k - t_0 [s]
  Eigen::Matrix3d R_0k = Eigen::Matrix3d::Identity();    // rotation of B_k in B_0
  Eigen::Vector3d dp_0k = Eigen::Vector3d::Zero();       // gravity-free position delta [m, B_0]
  Eigen::Matrix3d dR_dbg = Eigen::Matrix3d::Zero();      // Forster eq. 44 Jacobians
  Eigen::Matrix3d dp_dbg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dp_dba = Eigen::Matrix3d::Zero();
};

struct RefineRay {
  std::size_t landmark = 0;  // index into the landmarks
  std::size_t frame = 0;     // index into the frames
  Eigen::Vector3d f_B;       // unit ray direction in B_k (R_BC f_C)
};

struct RefineState {
  Eigen::Vector3d v0_B0 = Eigen::Vector3d::Zero();   // [m/s]
  Eigen::Vector3d g_B0 = Eigen::Vector3d::Zero();    // [m/s^2], |g| = G is kept
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();     // [rad/s]
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();     // [m/s^2]
  std::vector<Eigen::Vector3d> P_B0;                 // landmarks [m]
};

struct RefineProblem {
  std::vector<RefineFrame> frames;
  std::vector<RefineRay> rays;
  Eigen::Vector3d t_BC = Eigen::Vector3d::Zero();   // camera centre in B [m]
  double sigma_rad = 0.002;                         // angular noise of a ray (pixel sigma / focal) [rad]
  double huber_rad = 0.005;                         // Huber threshold on the angle [rad]
  double gyro_bias_sigma = 0.01;                    // prior [rad/s]
  double accel_bias_sigma = 0.2;                    // prior [m/s^2]
};

// Refines `state` in place (Ceres); returns false if the solve failed.
bool refine_motion_init(const RefineProblem& problem, RefineState& state, int max_iterations);

// Covariance of (v_0 [3], gravity on its tangent plane [2, m/s^2]) at `state` for an angular noise sigma_rad, with
// the landmarks and biases eliminated (Schur complement of the Gauss-Newton information, bias priors included).
Eigen::Matrix<double, 5, 5> motion_init_covariance(const RefineProblem& problem, const RefineState& state,
                                                   double sigma_rad);

// Angle [rad] between each ray and the direction from its camera centre to its landmark.
std::vector<double> ray_angles(const RefineProblem& problem, const RefineState& state);

}  // namespace twinslam::estimator
