#include "estimator_config.hpp"

#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/estimator/sliding_window_config_yaml.hpp"

namespace twinslam::estimator {

EstimatorNodeOptions EstimatorServiceConfig::for_replay(bool lockstep) const {
  EstimatorNodeOptions o = options;
  if (lockstep) o.estimator.max_solver_time_s = lockstep_max_solver_time_s;
  return o;
}

namespace {

void bind_fusion_fields(yaml::Fields& fields, GlobalFusionConfig& f) {
  fields.section("fusion")
      .flag("fuse_registrations", f.fuse_registrations)
      .flag("align_from_gnss", f.align_from_gnss)
      .flag("fuse_gnss", f.fuse_gnss)
      .flag("fuse_gnss_loose", f.fuse_gnss_loose)
      .number("realign_after_s", f.realign_after_s, "s")
      .flag("realign_on_readmitted_registration", f.realign_on_readmitted_registration)
      .number("realign_min_correction_m", f.realign_min_correction_m, "m")
      .number("realign_min_correction_deg", f.realign_min_correction_deg, "deg")
      .integer("declare_agreeing_registrations", f.declare_agreeing_registrations)
      .number("declare_max_correction_m", f.declare_max_correction_m, "m")
      .number("initial_pose_position_sigma_m", f.initial_pose_position_sigma_m, "m")
      .number("initial_pose_yaw_sigma_deg", f.initial_pose_yaw_sigma_deg, "deg")
      .number("gnss_alignment_sigma_scale", f.gnss_alignment_sigma_scale)
      .number("gnss_correlation_s", f.gnss_correlation_s, "s")
      .number("provisional_yaw_sigma_deg", f.provisional_yaw_sigma_deg, "deg")
      .number("aligner_converged_yaw_sigma_deg", f.aligner.converged_yaw_sigma_deg, "deg")
      .integer("aligner_min_pairs", f.aligner.min_pairs)
      .number("aligner_min_span_m", f.aligner.min_span_m, "m")
      .count("aligner_max_pairs", f.aligner.max_pairs)
      .number("registration_gate_max_mahalanobis_sq", f.registration_gate.max_mahalanobis_sq)
      .number("registration_gate_floor_m", f.registration_gate.floor_m, "m")
      .number("registration_gate_floor_deg", f.registration_gate.floor_deg, "deg")
      .number("registration_gate_max_correction_m", f.registration_gate.max_correction_m, "m")
      .number("registration_gate_max_correction_deg", f.registration_gate.max_correction_deg, "deg")
      .number("gnss_jump_sigmas", f.gnss_jump.jump_sigmas)
      .number("gnss_jump_min_m", f.gnss_jump.min_jump_m, "m")
      .number("gnss_jump_hold_s", f.gnss_jump.hold_s, "s")
      .number("registration_huber_delta", f.registration.huber_delta)
      .number("registration_max_reattach_s", f.registration.max_reattach_s, "s")
      .number("gnss_huber_delta", f.gnss.huber_delta)
      .number("gnss_max_dt_s", f.gnss.max_dt_s, "s")
      .number("loose_node_interval_s", f.loose.node_interval_s, "s")
      .integer("loose_window_nodes", f.loose.window_nodes)
      .number("loose_odometry_sigma_per_m", f.loose.odometry_sigma_per_m)
      .number("loose_odometry_min_sigma_m", f.loose.odometry_min_sigma_m, "m")
      .number("loose_odometry_deg_per_m", f.loose.odometry_deg_per_m, "deg/m")
      .number("loose_odometry_min_sigma_deg", f.loose.odometry_min_sigma_deg, "deg")
      .number("loose_prior_sigma_m", f.loose.prior_sigma_m, "m")
      .number("loose_prior_sigma_deg", f.loose.prior_sigma_deg, "deg")
      .number("loose_huber_delta", f.loose.huber_delta)
      .integer("loose_max_iterations", f.loose.max_iterations);
}

}  // namespace

void bind_estimator_service_config(yaml::Fields& fields, EstimatorServiceConfig& config) {
  bind_sliding_window_config(fields, config.options.estimator);
  fields.section("node")
      .milliseconds("imu_wait_ms", config.options.imu_wait)
      .number("lockstep_max_solver_time_s", config.lockstep_max_solver_time_s, "s")
      .milliseconds("registration_wait_ms", config.options.registration_wait)
      .milliseconds("registration_link_wait_ms", config.options.registration_link_wait)
      .integer("registration_give_up_after", config.options.registration_give_up_after)
      .number("checkpoint_every_s", config.options.checkpoint_every_s, "s");
  ResumeConfig& r = config.options.resume;
  fields.section("resume")
      .number("max_age_s", r.max_age_s, "s")
      .number("max_accel_mps2", r.max_accel_mps2, "m/s^2")
      .number("max_rate_degps", r.max_rate_degps, "deg/s")
      .number("velocity_sigma_mps", r.velocity_sigma_mps, "m/s")
      .number("tilt_sigma_deg", r.tilt_sigma_deg, "deg")
      .number("gyro_bias_sigma_radps", r.gyro_bias_sigma_radps, "rad/s")
      .number("accel_bias_sigma_mps2", r.accel_bias_sigma_mps2, "m/s^2");
  bind_fusion_fields(fields, config.options.fusion);
}

std::string changed_from_defaults(const EstimatorServiceConfig& config) {
  EstimatorServiceConfig now = config, defaults;
  yaml::Fields a("estimator"), b("estimator");
  bind_estimator_service_config(a, now);
  bind_estimator_service_config(b, defaults);
  return yaml::changed_values(a.values(), b.values());
}

EstimatorServiceConfig parse_estimator_service_config(const std::string& text, const std::string& file,
                                                      const EstimatorServiceConfig& base) {
  EstimatorServiceConfig c = base;
  yaml::Fields fields("estimator");
  bind_estimator_service_config(fields, c);
  fields.parse(text, file);
  validate_estimator_config(c.options.estimator, file);
  if (c.options.imu_wait.count() < 0) {
    throw InputError(where(file, 0, "estimator key 'node.imu_wait_ms': must be >= 0"));
  }
  try {
    c.options.fusion.validate();
  } catch (const InputError& e) {
    throw InputError(where(file, 0, std::string("estimator key 'fusion': ") + e.what()));
  }
  if (c.options.registration_give_up_after < 1) {
    throw InputError(where(file, 0, "estimator key 'node.registration_give_up_after': must be >= 1"));
  }
  if (!(c.options.checkpoint_every_s > 0.0)) {
    throw InputError(where(file, 0, "estimator key 'node.checkpoint_every_s': must be > 0"));
  }
  try {
    c.options.resume.validate();
  } catch (const InputError& e) {
    throw InputError(where(file, 0, std::string("estimator key ") + e.what()));
  }
  if (!(c.lockstep_max_solver_time_s > 0.0)) {
    throw InputError(where(file, 0, "estimator key 'node.lockstep_max_solver_time_s': must be > 0"));
  }
  return c;
}

EstimatorServiceConfig load_estimator_service_config(const std::string& path, const EstimatorServiceConfig& base) {
  return parse_estimator_service_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::estimator
