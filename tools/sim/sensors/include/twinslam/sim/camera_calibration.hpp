#pragma once
// What the dataset states about the camera versus what it was: the extrinsic and intrinsic calibration errors of the
// scenario (camera.extrinsic_error_*, camera.intrinsic_error_*). Images and ideal tracks are made with the true camera
// (camera_T_BC(scenario), sim_camera_config); mav0/cam0/sensor.yaml states calibrated_T_BC(scenario) and the true
// intrinsics changed by camera_intrinsic_errors(scenario).
#include <cstdint>

#include <Eigen/Geometry>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

// The true T_BC with a calibration error of exactly the configured size, in seeded directions (a random stream of
// scenario.seed of its own):  R_stated = Exp(extrinsic_error_deg * a) R_true  (a: unit axis in B), so the angle of
// R_true^T R_stated is extrinsic_error_deg;  t_stated = t_true + extrinsic_error_m * d  (d: unit direction in B).
// Both errors 0: the true T_BC, bit for bit.
Eigen::Isometry3d calibrated_T_BC(const Scenario& scenario);

// The intrinsic calibration error, applied to the true intrinsics as  fu' = focal_scale fu, fv' = focal_scale fv,
// (cu', cv') = (cu, cv) + principal_point_shift_px, c0' = c0 + k1_offset  (c0: the equidistant k1 or the radtan k1).
struct CameraIntrinsicErrors {
  double focal_scale = 1.0;                                          // 1 +- intrinsic_error_focal [-]
  Eigen::Vector2d principal_point_shift_px = Eigen::Vector2d::Zero();  // length intrinsic_error_px [px]
  double k1_offset = 0.0;                                            // +- intrinsic_error_k1, the focal's sign [-]
};
// One sign (for the focal and k1 errors alike, so they add, not cancel, off-axis) and the shift's direction drawn
// from a random stream of scenario.seed of its own (always drawn, so one key at 0 changes no other draw). All three
// keys 0: no error (1, 0, 0) exactly.
CameraIntrinsicErrors camera_intrinsic_errors(const Scenario& scenario);

}  // namespace twinslam::sim
