#pragma once
// IMU measurement, bias and noise model shared by the tracking frontend (gyro prediction) and the estimator
// (preintegration, factors). In common/ so that neither service includes the other.
#include <cstdint>
#include <filesystem>

#include <Eigen/Core>

namespace twinslam::imu {

// One IMU reading. Measurement model (Forster et al., TRO 2017, Sec. IV):
//   gyro_B  = omega_WB_B + b_g + eta_g,   accel_B = R_WB^T (a_W - g_W) + b_a + eta_a.
struct ImuSample {
  std::int64_t stamp_ns = 0;
  Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();   // body rate in B [rad/s]
  Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();  // specific force in B [m/s^2]
};

// Slowly varying sensor biases, expressed in B.
struct ImuBias {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // b_g [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // b_a [m/s^2]
};

// Continuous-time noise densities of the IMU, SI units, named like the keys of EuRoC's imu0/sensor.yaml.
// Preintegration discretizes them with each sample interval dt: Cov(eta_d) = density^2 / dt for the white noise and
// Cov(b_j - b_i) = walk^2 * (t_j - t_i) for the bias random walk (Forster et al., Sec. IV and the bias
// random-walk term of the IMU factor).
// Defaults: the ADIS16448 of EuRoC (imu0/sensor.yaml).
struct ImuNoise {
  double gyroscope_noise_density = 1.6968e-04;     // [rad / s / sqrt(Hz)]
  double gyroscope_random_walk = 1.9393e-05;       // [rad / s^2 / sqrt(Hz)]
  double accelerometer_noise_density = 2.0000e-3;  // [m / s^2 / sqrt(Hz)]
  double accelerometer_random_walk = 3.0000e-3;    // [m / s^3 / sqrt(Hz)]
  double rate_hz = 200.0;                          // nominal sample rate [Hz]

  // Throws twinslam::InputError naming the first field that is not finite and positive.
  void validate() const;
};

// Reads an EuRoC imu0/sensor.yaml (including its OpenCV-style "%YAML:1.0" first line). Every noise key is required;
// a missing, non-numeric or non-positive value throws twinslam::InputError naming the file and the key.
ImuNoise load_imu_noise(const std::filesystem::path& sensor_yaml);

}  // namespace twinslam::imu
