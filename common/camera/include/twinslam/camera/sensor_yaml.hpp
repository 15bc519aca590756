#pragma once
// EuRoC ASL camera `sensor.yaml` (also written by Kalibr and by `twinslam sim`):
//   camera_model: pinhole                      (the only projection; fisheye = pinhole + equidistant distortion)
//   distortion_model: radial-tangential | radtan | equidistant | fisheye
//   intrinsics: [fu, fv, cu, cv]               px
//   distortion_coefficients: [c0, c1, c2, c3]  k1 k2 p1 p2 | k1 k2 k3 k4
//   resolution: [width, height]                px
//   T_BS: {cols: 4, rows: 4, data: [16 numbers, row-major]}   body <- camera
//   rate_hz: 20
#include <filesystem>

#include "twinslam/camera/camera_config.hpp"

namespace twinslam {

// Reads and validates the file. An OpenCV-style first line "%YAML:1.0" (as in the EuRoC files) is skipped: it is
// not valid YAML and yaml-cpp rejects it. Throws InputError "FILE[:LINE]: key 'K': what" on any bad or missing key,
// wrong count, non-finite number or a T_BS that is not a rigid transform.
CameraConfig read_camera_sensor_yaml(const std::filesystem::path& file);

// Writes `config` in the same format (without the "%YAML:1.0" line, so any YAML parser reads it), numbers in the
// shortest form that reads back to the same double. Validates first; throws InputError if the file cannot be written.
void write_camera_sensor_yaml(const std::filesystem::path& file, const CameraConfig& config);

}  // namespace twinslam
