#pragma once
// The estimator's names for the IMU types, which live in common/imu (shared with the tracking frontend, so neither
// service includes the other).
#include "twinslam/imu/imu_types.hpp"

namespace twinslam::estimator {

using imu::ImuBias;
using imu::ImuNoise;
using imu::ImuSample;
using imu::load_imu_noise;

}  // namespace twinslam::estimator
