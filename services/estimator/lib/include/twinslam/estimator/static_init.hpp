#pragma once
// Static initialization: when the platform is at rest (the EuRoC V1_01 excerpt starts so), the mean accelerometer
// reading is the specific force -R_LB^T g_L, which fixes roll and pitch of R_LB (yaw is unobservable and set to 0,
// as L is defined gravity-aligned with identity heading at initialization), and the mean gyro reading is the gyro
// bias (the Earth's rate, 7.3e-5 rad/s, is below the sensors' bias stability and ignored). The accelerometer bias
// cannot be separated from gravity at rest and starts at zero.
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/estimator/imu_types.hpp"

namespace twinslam::estimator {

struct StaticInitConfig {
  double window_s = 1.0;              // rest must last this long [s]
  // A multicopter "at rest" with spinning rotors vibrates: on the EuRoC excerpt's first 1.5 s the specific force
  // has up to 1.0 m/s^2 and the rate 0.08 rad/s per-axis standard deviation. The thresholds follow OpenVINS's
  // EuRoC setting (1.5 m/s^2); a visual stillness check can tighten this once tracks are available.
  double max_accel_std_mps2 = 1.5;    // per-axis standard deviation of the specific force at rest [m/s^2]
  double max_gyro_std_radps = 0.2;    // per-axis standard deviation of the rate at rest [rad/s]
  double gravity_mps2 = 9.81;         // |g| [m/s^2]
  double max_gravity_error_mps2 = 0.5;  // | |mean accel| - |g| | allowed (accelerometer scale/bias) [m/s^2]
  void validate() const;              // throws InputError naming the field
};

struct StaticInitResult {
  std::int64_t stamp_ns = 0;          // end of the rest window: the initial state's time
  Eigen::Quaterniond q_LB = Eigen::Quaterniond::Identity();  // roll/pitch from gravity, yaw 0
  ImuBias bias;                       // gyro bias from the mean rate; accel bias 0
};

// Looks at the last `window_s` of `samples` (sorted by stamp). Returns a result if the platform was at rest.
std::optional<StaticInitResult> try_static_init(const std::vector<ImuSample>& samples, const StaticInitConfig& cfg);

}  // namespace twinslam::estimator
