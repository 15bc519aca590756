#pragma once
// Configuration of the sliding-window visual-inertial estimator (issue 5): one struct, validated in one place.
#include <Eigen/Geometry>

#include "twinslam/estimator/imu_types.hpp"
#include "twinslam/estimator/keyframe_policy.hpp"
#include "twinslam/estimator/landmark_horizon.hpp"
#include "twinslam/estimator/marginalization.hpp"
#include "twinslam/estimator/motion_init.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "twinslam/estimator/static_init.hpp"
#include "twinslam/estimator/triangulation.hpp"

namespace twinslam::estimator {

struct SlidingWindowConfig {
  int window_keyframes = 8;            // keyframes kept before the oldest is marginalized
  int max_solver_iterations = 8;       // Levenberg-Marquardt iterations per frame
  double max_solver_time_s = 0.02;     // solver time cap per frame [s]
  // Relative cost decrease below which a solve stops. The window starts from the previous solution plus IMU
  // prediction, so Ceres' default 1e-6 spent most iterations on changes far below the noise: 1e-4 cut the median time
  // per frame about 3x on the simulated flight at the same accuracy (test_sliding_window), and 1e-3 another 25-45 %
  // on city-loops with ideal tracks (bench_motion_init_tiny DIR, alternating runs: median 6.1-9.4 ms vs 7.7-13.8 ms)
  // with the same ATE (1.641 vs 1.659 m over 504 m).
  double solver_function_tolerance = 1e-3;
  double focal_px = 460.0;             // fu of the camera: px per radian, converts angles to px [px/rad]
  double pixel_sigma = 1.0;            // feature noise [px]
  ImuNoise imu;                        // continuous-time IMU noise (EuRoC imu0/sensor.yaml keys)
  // IMU gaps (preintegration.hpp): a step between samples longer than imu_gap_s is a gap, integrated with the
  // unmeasured motion's sigmas below and reported (ODOM_FAULT_IMU_GAP).
  double imu_gap_s = 0.05;             // [s]
  double imu_gap_gyro_sigma = 0.5;     // [rad/s]
  double imu_gap_accel_sigma = 3.0;    // [m/s^2]
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();  // camera in body (nominal, from the dataset)
  // Online calibration of the camera rotation (camera_calibration.hpp): prior sigma per axis of R_BC's correction
  // around the nominal T_BC [deg]; 0 keeps R_BC fixed.
  double camera_rotation_sigma_deg = 0.0;
  // Online correction of the intrinsic calibration (lens_calibration.hpp): prior sigmas of the stated focal length
  // (relative), k1 [1/rad^2] and principal point [px]; 0 keeps that part as stated. By default k1 alone is estimated.
  // On the forward-looking, gently accelerating city flights a focal-length correction trades with the VIO's metric
  // scale (under forward motion, angles scaled by 1 + c look like a path scaled by 1 / (1 + c)) and drifted to -1.6 %
  // (true -0.3 %; ATE 0.78 -> 3.6 m on city-loops), and the principal point with the camera's mounting (18 px). k1
  // alone (0.005, with the two guards below) settles at -0.003 (true -0.002 plus the focal error's share): city-loops
  // vio 0.778 -> 0.389 m, vio-twin 0.526 -> 0.327 m (README, Online lens calibration).
  double lens_scale_sigma = 0.0;       // [1] relative focal-length error
  double lens_k1_sigma = 0.005;        // [1/rad^2] first radial coefficient on the equidistant angle
  double lens_center_sigma_px = 0.0;   // [px] principal point
  // The lens values are estimated only while the camera's optical axis spans at least this angle over the window's
  // frames (0: always), and held otherwise: a rotating camera sweeps a landmark across the image, which separates the
  // lens's radial profile from depth and scale; straight forward flight does not (on wrong-twin-aliased, a straight
  // street seen through an ideal lens, k1 estimated throughout drifted to -0.0055 and every accepted registration came
  // out 4.5-5.8 m off).
  double lens_excitation_deg = 10.0;   // [deg]
  // Nor in the first seconds after a (re)start, while the biases, gravity and metric scale settle: a lens freed then
  // takes up their errors. On wrong-twin-aliased (ideal lens; the first 10 s turn the camera up to 20 deg) k1 freed from
  // the start put the 10 s world alignment 3.0 m off (0.32 m held) and vio-twin at 1.47 m (0.33 m).
  double lens_settle_s = 20.0;         // [s]
  // Whether any part of the lens is estimated (a lens_*_sigma > 0).
  bool estimates_lens() const { return lens_scale_sigma > 0.0 || lens_k1_sigma > 0.0 || lens_center_sigma_px > 0.0; }
  // The world alignment T_WL as a random walk: each time the oldest keyframe is marginalized, the prior's covariance of
  // T_WL grows by these squared times the seconds it spans. Why: L drifts from W (the VIO's yaw and position drift),
  // so what old registrations and fixes said of T_WL goes stale; without it their information piled up in the prior and
  // held T_WL while the estimate's heading drifted 2 deg in 200 s on city-loops, refusing the registrations that saw it.
  // 0 keeps T_WL constant. City-loops vio-twin (ideal tracks, realistic sensors) for 0 / (0.02, 0.01) / (0.05, 0.02) /
  // (0.1, 0.02) / (0.1, 0.05) / (0.2, 0.05): ATE 0.820 / 0.660 / 0.587 / 0.526 / 0.546 / 0.536 m, 1.43 / 1.10 / 0.87 /
  // 0.78 / 0.80 / 0.76 deg. 0.05 m/sqrt(s) let a building missing from the twin shift the change report by 5.01 m.
  double world_alignment_random_walk_deg = 0.1;  // [deg/sqrt(s)] heading of T_WL
  double world_alignment_random_walk_m = 0.02;   // [m/sqrt(s)] each axis of p_WL
  double gravity_mps2 = 9.81;          // |g| [m/s^2]

  // Initialization. A rest window of 0.5 s suffices for the simulator's ~0.8 s of rest at the start.
  double static_window_s = 0.5;        // [s]
  // The IMU rest test alone accepts gentle motion (its thresholds allow a hovering multicopter's vibration), so rest
  // also needs the features to stand still over the static window: mean bearing change of common tracks from every
  // frame of the last static_window_s, with the gyro's rotation removed (visual_rest.hpp) [px].
  double max_rest_feature_motion_px = 2.0;
  // The gyro bias fitted to the bearings in that test: more than this is motion, not bias [rad/s]. Above MEMS gyro
  // biases (consumer grade ~0.009 rad/s per axis; EuRoC's ADIS16448 0.08 rad/s); a sideways flight past a flat
  // facade 20 m away at 3 m/s (0.15 rad/s) looks like such a turn, and only depth differences tell it from one.
  double max_rest_gyro_bias_radps = 0.15;
  double init_timeout_s = 5.0;         // neither rest nor a motion initialization for this long -> reported [s]
  // In motion, the closed-form visual-inertial initialization (motion_init.hpp) starts the window instead.
  MotionInitConfig motion_init;
  // Prior on the first keyframe: position and yaw fix the gauge of L (L's definition); roll/pitch from gravity.
  // These are the static initialization's; a motion initialization uses motion_init's velocity and tilt sigmas.
  double init_position_sigma_m = 1e-3;      // [m]
  double init_yaw_sigma_rad = 1e-3;         // [rad]
  double init_roll_pitch_sigma_rad = 0.02;  // [rad] (about 1 deg: the static init's accuracy)
  double init_velocity_sigma_mps = 0.05;    // at rest [m/s]
  double init_gyro_bias_sigma = 0.01;       // [rad/s]
  double init_accel_bias_sigma = 0.2;       // [m/s^2]

  // Landmarks and outliers.
  double outlier_threshold_px = 3.0;   // observations farther than this after a solve are removed [px]
  int min_observations = 2;            // keyframe/frame observations needed to triangulate (anchor included)
  int max_landmarks = 150;             // triangulated landmarks kept in the window (VINS-Mono tracks 150)
  // A keyframe at least this often even without parallax (hovering), so preintegration intervals stay short [s].
  double max_keyframe_interval_s = 1.0;
  // A frame with fewer features (a black or saturated image, a covered lens: issue 15) never becomes a keyframe: it
  // would push the informative keyframes out of the window (2 s of black frames made the ATE 2.3x the clean run's on
  // tiny); the IMU carries the estimate from the last keyframe to the next textured frame. Reported as
  // ODOM_FAULT_FEW_FEATURES.
  int min_keyframe_features = 10;

  // Zero-velocity update: at rest (the EuRoC excerpt hovers on the ground for its first seconds) no landmark has
  // parallax, so only the IMU would constrain the window and the accelerometer bias would drift it. When at least
  // `zero_velocity_min_tracks` tracks moved less than `zero_velocity_max_motion_px` on average since the last keyframe,
  // at least `zero_velocity_min_interval_s` earlier, the frame gets a factor v_L = 0 (sigma below). The interval keeps
  // slow flight far from the scene out (1 m/s at 100 m moves a feature 1 px in 0.2 s at f = 460 px).
  bool zero_velocity = true;
  double zero_velocity_max_motion_px = 0.5;  // [px]
  double zero_velocity_min_interval_s = 0.25;  // [s]
  int zero_velocity_min_tracks = 20;
  double zero_velocity_sigma_mps = 0.01;  // [m/s]

  // Divergence: any of these after a solve resets the estimator (status kReinitializing).
  double max_speed_mps = 50.0;               // |v_L| [m/s]
  double max_gyro_bias_radps = 0.2;          // |b_g| [rad/s]
  double max_accel_bias_mps2 = 2.0;          // |b_a| [m/s^2]
  // Median (not mean: a few gross outliers before their removal must not count as divergence) reprojection error of
  // the window's observations after a solve [px].
  double max_median_reprojection_px = 10.0;

  KeyframePolicyConfig keyframe;       // focal_px is overwritten with focal_px above
  TriangulationConfig triangulation;   // focal_px likewise
  MarginalizationConfig marginalization;
  LandmarkHorizonConfig local_map;     // which landmarks a LocalMap carries (registration's source cloud)

  void validate() const;  // throws twinslam::InputError naming the bad field
  ReprojectionNoise reprojection_noise() const;
  StaticInitConfig static_init() const;
};

}  // namespace twinslam::estimator
