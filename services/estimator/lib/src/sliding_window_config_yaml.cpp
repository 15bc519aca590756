#include "twinslam/estimator/sliding_window_config_yaml.hpp"

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {
namespace {

void bind_keyframe(yaml::Fields& f, KeyframePolicyConfig& c) {
  f.number("min_mean_parallax_px", c.min_mean_parallax_px, "px").number("min_tracked_ratio", c.min_tracked_ratio);
}

void bind_triangulation(yaml::Fields& f, TriangulationConfig& c) {
  f.number("min_parallax_deg", c.min_parallax_deg, "deg")
      .number("max_error_px", c.max_error_px, "px")
      .number("min_depth_m", c.min_depth_m, "m")
      .number("max_depth_m", c.max_depth_m, "m")
      .integer("max_iterations", c.max_iterations);
}

void bind_motion_init(yaml::Fields& f, MotionInitConfig& c) {
  f.flag("enabled", c.enabled)
      .number("window_s", c.window_s, "s")
      .number("min_span_s", c.min_span_s, "s")
      .integer("min_landmarks", c.min_landmarks)
      .integer("max_frames", c.max_frames)
      .integer("max_landmarks", c.max_landmarks)
      .integer("min_observations", c.min_observations)
      .number("min_parallax_deg", c.min_parallax_deg, "deg")
      .number("max_gravity_norm_error", c.max_gravity_norm_error)
      .number("max_tilt_sigma_deg", c.max_tilt_sigma_deg, "deg")
      .number("max_velocity_sigma_mps", c.max_velocity_sigma_mps, "m/s")
      .number("max_median_error_px", c.max_median_error_px, "px")
      .number("min_excitation_mps2", c.min_excitation_mps2, "m/s^2")
      .integer("max_refine_iterations", c.max_refine_iterations)
      .number("velocity_prior_sigma_mps", c.velocity_prior_sigma_mps, "m/s")
      .number("tilt_prior_sigma_rad", c.tilt_prior_sigma_rad, "rad");
}

void bind_solver_and_init(yaml::Fields& f, SlidingWindowConfig& c) {
  f.integer("window_keyframes", c.window_keyframes)
      .integer("max_solver_iterations", c.max_solver_iterations)
      .number("max_solver_time_s", c.max_solver_time_s, "s")
      .number("solver_function_tolerance", c.solver_function_tolerance)
      .number("pixel_sigma", c.pixel_sigma, "px")
      .number("camera_rotation_sigma_deg", c.camera_rotation_sigma_deg, "deg")
      .number("lens_scale_sigma", c.lens_scale_sigma)
      .number("lens_k1_sigma", c.lens_k1_sigma, "1/rad^2")
      .number("lens_center_sigma_px", c.lens_center_sigma_px, "px")
      .number("lens_excitation_deg", c.lens_excitation_deg, "deg")
      .number("lens_settle_s", c.lens_settle_s, "s")
      .number("world_alignment_random_walk_deg", c.world_alignment_random_walk_deg, "deg/sqrt(s)")
      .number("world_alignment_random_walk_m", c.world_alignment_random_walk_m, "m/sqrt(s)")
      .number("gravity_mps2", c.gravity_mps2, "m/s^2")
      .number("static_window_s", c.static_window_s, "s")
      .number("max_rest_feature_motion_px", c.max_rest_feature_motion_px, "px")
      .number("max_rest_gyro_bias_radps", c.max_rest_gyro_bias_radps, "rad/s")
      .number("init_timeout_s", c.init_timeout_s, "s")
      .number("init_position_sigma_m", c.init_position_sigma_m, "m")
      .number("init_yaw_sigma_rad", c.init_yaw_sigma_rad, "rad")
      .number("init_roll_pitch_sigma_rad", c.init_roll_pitch_sigma_rad, "rad")
      .number("init_velocity_sigma_mps", c.init_velocity_sigma_mps, "m/s")
      .number("init_gyro_bias_sigma", c.init_gyro_bias_sigma, "rad/s")
      .number("init_accel_bias_sigma", c.init_accel_bias_sigma, "m/s^2");
}

void bind_landmarks_and_limits(yaml::Fields& f, SlidingWindowConfig& c) {
  f.number("outlier_threshold_px", c.outlier_threshold_px, "px")
      .integer("min_observations", c.min_observations)
      .integer("max_landmarks", c.max_landmarks)
      .number("max_keyframe_interval_s", c.max_keyframe_interval_s, "s")
      .integer("min_keyframe_features", c.min_keyframe_features)
      .number("imu_gap_s", c.imu_gap_s, "s")
      .number("imu_gap_gyro_sigma", c.imu_gap_gyro_sigma, "rad/s")
      .number("imu_gap_accel_sigma", c.imu_gap_accel_sigma, "m/s^2")
      .flag("zero_velocity", c.zero_velocity)
      .number("zero_velocity_max_motion_px", c.zero_velocity_max_motion_px, "px")
      .number("zero_velocity_min_interval_s", c.zero_velocity_min_interval_s, "s")
      .integer("zero_velocity_min_tracks", c.zero_velocity_min_tracks)
      .number("zero_velocity_sigma_mps", c.zero_velocity_sigma_mps, "m/s")
      .number("max_speed_mps", c.max_speed_mps, "m/s")
      .number("max_gyro_bias_radps", c.max_gyro_bias_radps, "rad/s")
      .number("max_accel_bias_mps2", c.max_accel_bias_mps2, "m/s^2")
      .number("max_median_reprojection_px", c.max_median_reprojection_px, "px");
}

}  // namespace

void bind_sliding_window_config(yaml::Fields& fields, SlidingWindowConfig& config) {
  bind_solver_and_init(fields, config);
  bind_landmarks_and_limits(fields, config);
  bind_keyframe(fields.section("keyframe"), config.keyframe);
  bind_triangulation(fields.section("triangulation"), config.triangulation);
  fields.section("marginalization").number("min_eigenvalue", config.marginalization.min_eigenvalue);
  bind_motion_init(fields.section("motion_init"), config.motion_init);
  fields.section("local_map")
      .number("horizon_s", config.local_map.horizon_s, "s")
      .number("horizon_m", config.local_map.horizon_m, "m")
      .integer("max_landmarks", config.local_map.max_landmarks)
      .flag("follow_window", config.local_map.follow_window);
}

void validate_estimator_config(const SlidingWindowConfig& config, const std::string& file) {
  try {
    config.validate();
  } catch (const InputError& e) {
    throw InputError(where(file, 0, e.what()));
  }
}

SlidingWindowConfig parse_estimator_config(const std::string& text, const std::string& file,
                                           const SlidingWindowConfig& base) {
  SlidingWindowConfig config = base;
  yaml::Fields fields("estimator");
  bind_sliding_window_config(fields, config);
  fields.parse(text, file);
  validate_estimator_config(config, file);
  return config;
}

SlidingWindowConfig load_estimator_config(const std::string& path, const SlidingWindowConfig& base) {
  return parse_estimator_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::estimator
