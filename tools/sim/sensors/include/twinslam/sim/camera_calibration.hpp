#pragma once
// What the dataset states about the camera versus what it was: the extrinsic calibration error of the scenario
// (camera.extrinsic_error_deg, camera.extrinsic_error_m). Images and ideal tracks are made with the true extrinsics
// camera_T_BC(scenario); mav0/cam0/sensor.yaml states calibrated_T_BC(scenario).
#include <cstdint>

#include <Eigen/Geometry>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

// The true T_BC with a calibration error of exactly the configured size, in seeded directions (a random stream of
// scenario.seed of its own):  R_stated = Exp(extrinsic_error_deg * a) R_true  (a: unit axis in B), so the angle of
// R_true^T R_stated is extrinsic_error_deg;  t_stated = t_true + extrinsic_error_m * d  (d: unit direction in B).
// Both errors 0: the true T_BC, bit for bit.
Eigen::Isometry3d calibrated_T_BC(const Scenario& scenario);

}  // namespace twinslam::sim
