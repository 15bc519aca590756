#pragma once
// The simulated camera of a scenario as a calibration the rest of twinslam reads (EuRoC sensor.yaml keys).
#include "twinslam/camera/camera_config.hpp"
#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

// fisheye-equidistant: ideal equidistant lens (theta_d = theta), fu = (width/2) / (fov/2 in rad);
// pinhole-radtan: fu = (width/2) / tan(fov/2) with a mild barrel distortion (k1 = -0.05, k2 = 0.01), as a real
// wide lens has, so the tracker's undistortion is exercised. Square pixels, principal point at the centre.
// T_BC from the scenario (camera_T_BC).
CameraConfig sim_camera_config(const Scenario& scenario);

// What mav0/cam0/sensor.yaml states: sim_camera_config's intrinsics with camera_intrinsic_errors(scenario) applied
// (camera_calibration.hpp) and the extrinsics calibrated_T_BC(scenario).
CameraConfig calibrated_sim_camera_config(const Scenario& scenario);

}  // namespace twinslam::sim
