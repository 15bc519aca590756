#pragma once
// The camera module's one config struct: intrinsics (what camera models need), extrinsics and rate (what the
// estimator and the simulator need). It is what an EuRoC `mav0/cam0/sensor.yaml` holds (see sensor_yaml.hpp).
#include <Eigen/Geometry>
#include <string>

#include "twinslam/camera/camera_model.hpp"

namespace twinslam {

struct CameraConfig {
  CameraIntrinsics intrinsics;
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();  // body (IMU) <- camera; EuRoC's T_BS. Metres.
  double rate_hz = 20.0;                                    // frames per second
};

// Tolerance on |R^T R - I| (max abs entry) for T_BC's rotation: EuRoC prints rotations with ~12 digits.
constexpr double kRotationOrthonormalTol = 1e-6;

// The one place where camera settings are checked. Throws InputError "SOURCE: key 'K': what" naming the EuRoC key
// (resolution, intrinsics, distortion_coefficients, T_BS, rate_hz) of the first bad value.
void validate(const CameraIntrinsics& intrinsics, const std::string& source);
void validate(const CameraConfig& config, const std::string& source);

}  // namespace twinslam
