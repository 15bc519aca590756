#include "twinslam/estimator/sliding_window_config.hpp"

#include <cmath>
#include <string>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {

void SlidingWindowConfig::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw InputError(std::string("sliding_window.") + name + ": must be > 0");
  };
  if (window_keyframes < 2) throw InputError("sliding_window.window_keyframes: must be >= 2");
  local_map.validate("sliding_window");
  if (max_solver_iterations < 1) throw InputError("sliding_window.max_solver_iterations: must be >= 1");
  if (min_observations < 2) throw InputError("sliding_window.min_observations: must be >= 2");
  if (max_landmarks < 1) throw InputError("sliding_window.max_landmarks: must be >= 1");
  positive(max_solver_time_s, "max_solver_time_s");
  positive(solver_function_tolerance, "solver_function_tolerance");
  positive(focal_px, "focal_px");
  positive(pixel_sigma, "pixel_sigma");
  positive(gravity_mps2, "gravity_mps2");
  positive(static_window_s, "static_window_s");
  positive(init_timeout_s, "init_timeout_s");
  positive(max_rest_feature_motion_px, "max_rest_feature_motion_px");
  positive(max_rest_gyro_bias_radps, "max_rest_gyro_bias_radps");
  positive(init_position_sigma_m, "init_position_sigma_m");
  positive(init_yaw_sigma_rad, "init_yaw_sigma_rad");
  positive(init_roll_pitch_sigma_rad, "init_roll_pitch_sigma_rad");
  positive(init_velocity_sigma_mps, "init_velocity_sigma_mps");
  positive(init_gyro_bias_sigma, "init_gyro_bias_sigma");
  positive(init_accel_bias_sigma, "init_accel_bias_sigma");
  positive(outlier_threshold_px, "outlier_threshold_px");
  positive(max_keyframe_interval_s, "max_keyframe_interval_s");
  positive(imu_gap_s, "imu_gap_s");
  if (min_keyframe_features < 0) throw InputError("sliding_window.min_keyframe_features: must be >= 0");
  positive(imu_gap_gyro_sigma, "imu_gap_gyro_sigma");
  positive(imu_gap_accel_sigma, "imu_gap_accel_sigma");
  positive(max_speed_mps, "max_speed_mps");
  positive(zero_velocity_max_motion_px, "zero_velocity_max_motion_px");
  positive(zero_velocity_min_interval_s, "zero_velocity_min_interval_s");
  positive(zero_velocity_sigma_mps, "zero_velocity_sigma_mps");
  if (zero_velocity_min_tracks < 1) throw InputError("sliding_window.zero_velocity_min_tracks: must be >= 1");
  positive(max_gyro_bias_radps, "max_gyro_bias_radps");
  positive(max_accel_bias_mps2, "max_accel_bias_mps2");
  positive(max_median_reprojection_px, "max_median_reprojection_px");
  if (!T_BC.matrix().allFinite()) throw InputError("sliding_window.T_BC: not finite");
  if (!(camera_rotation_sigma_deg >= 0.0) || !(camera_rotation_sigma_deg <= 10.0)) {
    throw InputError("sliding_window.camera_rotation_sigma_deg: must be in [0, 10] (0: fixed R_BC)");
  }
  const double lens[] = {lens_scale_sigma, lens_k1_sigma, lens_center_sigma_px};
  const char* lens_keys[] = {"lens_scale_sigma", "lens_k1_sigma", "lens_center_sigma_px"};
  for (int i = 0; i < 3; ++i) {
    if (!(lens[i] >= 0.0) || !(lens[i] <= 100.0)) {
      throw InputError(std::string("sliding_window.") + lens_keys[i] + ": must be in [0, 100] (0: as stated)");
    }
  }
  if (!(lens_excitation_deg >= 0.0) || !(lens_excitation_deg <= 180.0)) {
    throw InputError("sliding_window.lens_excitation_deg: must be in [0, 180] deg (0: always estimated)");
  }
  if (!(lens_settle_s >= 0.0) || !(lens_settle_s <= 3600.0)) {
    throw InputError("sliding_window.lens_settle_s: must be in [0, 3600] s");
  }
  if (estimates_lens() && camera_rotation_sigma_deg > 0.0) {
    throw InputError("sliding_window.camera_rotation_sigma_deg: the camera rotation and the lens cannot both be "
                     "calibrated online (not implemented); set it to 0, or every lens_*_sigma to 0 "
                     "(lens_k1_sigma is 0.005 by default)");
  }
  if (!(world_alignment_random_walk_deg >= 0.0) || !(world_alignment_random_walk_deg <= 10.0)) {
    throw InputError("sliding_window.world_alignment_random_walk_deg: must be in [0, 10] deg/sqrt(s) (0: T_WL constant)");
  }
  if (!(world_alignment_random_walk_m >= 0.0) || !(world_alignment_random_walk_m <= 10.0)) {
    throw InputError("sliding_window.world_alignment_random_walk_m: must be in [0, 10] m/sqrt(s) (0: T_WL constant)");
  }
  imu.validate();
  reprojection_noise().validate();
  static_init().validate();
  motion_init.validate();
  KeyframePolicyConfig k = keyframe;
  k.focal_px = focal_px;
  k.validate();
  TriangulationConfig t = triangulation;
  t.focal_px = focal_px;
  t.validate();
  marginalization.validate();
}

ReprojectionNoise SlidingWindowConfig::reprojection_noise() const {
  ReprojectionNoise n;
  n.focal_px = focal_px;
  n.pixel_sigma = pixel_sigma;
  return n;
}

StaticInitConfig SlidingWindowConfig::static_init() const {
  StaticInitConfig c;
  c.window_s = static_window_s;
  c.gravity_mps2 = gravity_mps2;
  return c;
}

}  // namespace twinslam::estimator
