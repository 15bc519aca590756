#pragma once
// Visual-inertial initialization in motion, without GNSS and without rest: the closed-form solution of Martinelli
// (IJCV 2014) as refined by Kaiser et al. (RA-L 2017), with the VINS-Mono gravity refinement on the sphere |g| = G.
//
// Over the last ~2 s of frames, the gyroscope gives the rotations R_0k of B_k in B_0 and the preintegrated accelerometer
// gives dp_0k, so the camera centre of frame k in B_0 is c_k = v_0 t_k + g t_k^2 / 2 + dp_0k + R_0k t_BC, linear in
// the unknown initial velocity v_0 and gravity g (both in B_0). Every observation f_kj of a landmark P_j says P_j lies
// on the ray from c_k along d_kj = R_0k R_BC f_kj: [d_kj]x (P_j - c_k) = 0, linear in (v_0, g, P_j). The landmarks are
// eliminated by a Schur complement (3x3 blocks), leaving 6 unknowns. That linear solution (which ignores the IMU
// biases and is biased by noisy ray directions) starts a small maximum-likelihood bundle adjustment on the ray angles
// over v_0, g, both IMU biases and the landmarks (motion_init_refine.hpp). Metric scale comes from the accelerometer,
// so the solution exists only with enough acceleration and parallax: the refined solution's covariance and its rays'
// residuals decide whether it is trusted. The window gets the gyro bias; the accelerometer bias, barely separable from
// gravity in 2 s, starts at zero there as after a static initialization.
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/imu_types.hpp"

namespace twinslam::estimator {

struct MotionInitConfig {
  bool enabled = true;
  double window_s = 2.0;               // frames of this much history are used [s]
  double min_span_s = 1.5;             // no attempt before this much history [s] (1.0 s gave 3 deg errors)
  int min_landmarks = 25;              // landmarks with enough parallax for the solve
  // Cost bounds: frames evenly picked from the window and the longest-tracked landmarks. 15 frames x 120 landmarks
  // keep one attempt near 20 ms; more did not improve gravity or velocity on simulated flights.
  int max_frames = 15;
  int max_landmarks = 120;
  int min_observations = 3;            // per landmark, within the window
  double min_parallax_deg = 2.0;       // ray angle span of a landmark over the window [deg]
  double max_gravity_norm_error = 0.1; // | |g| / G - 1 | of the unconstrained solution
  double max_tilt_sigma_deg = 1.5;     // 1-sigma of the gravity direction [deg]
  double max_velocity_sigma_mps = 0.25;// 1-sigma of the velocity, per axis [m/s] (mostly the accel bias's share)
  double max_median_error_px = 2.0;    // median ray error of the solution [px]
  // RMS gravity-free acceleration over the window [m/s^2]: below it the metric scale is not determined (steady
  // flight) and no solution is trusted, whatever its covariance says (VINS-Mono warns at a 0.25 m/s^2 spread).
  double min_excitation_mps2 = 0.25;
  double pixel_sigma = 1.0;            // feature noise [px] (the estimator sets its own)
  int max_refine_iterations = 10;      // of the maximum-likelihood refinement (motion_init_refine.hpp)
  // The window's prior on the initial velocity and roll / pitch after a motion init is the solution's own 1-sigma,
  // but not below these floors [m/s], [rad].
  double velocity_prior_sigma_mps = 0.05;
  double tilt_prior_sigma_rad = 0.005;
  void validate() const;               // throws InputError naming the field
};

struct MotionInitFrame {
  std::int64_t stamp_ns = 0;
  std::unordered_map<std::int64_t, Eigen::Vector3d> bearings;  // feature id -> unit bearing f_C
};

struct MotionInitResult {
  ImuState state;                      // of the newest frame, in L (gravity-aligned, yaw 0, p_L = 0 at that frame)
  Eigen::Vector3d g_B0 = Eigen::Vector3d::Zero();  // gravity in the oldest frame's body axes [m/s^2]
  double tilt_sigma_deg = 0.0;
  double velocity_sigma_mps = 0.0;
  double median_error_px = 0.0;
  double excitation_mps2 = 0.0;        // RMS gravity-free acceleration over the window [m/s^2]
  int landmarks = 0;
};

// frames: sorted by stamp, the newest last; imu sorted and covering [frames.front(), frames.back()]. gravity_mps2: G.
// focal_px converts angles to pixels. Returns nothing when the data do not determine the state well enough.
std::optional<MotionInitResult> try_motion_init(const std::vector<MotionInitFrame>& frames,
                                                const std::vector<ImuSample>& imu, const Eigen::Isometry3d& T_BC,
                                                const ImuNoise& noise, double gravity_mps2, double focal_px,
                                                const MotionInitConfig& config);

}  // namespace twinslam::estimator
