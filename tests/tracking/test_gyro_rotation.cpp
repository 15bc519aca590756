// Gyro integration between frames: a constant body rate gives R_prev_curr_C = R_CB Exp(w dt) R_BC exactly.
#include <gtest/gtest.h>

#include <vector>

#include "twinslam/geometry/so3.hpp"
#include "twinslam/tracking/gyro_rotation.hpp"

namespace twinslam::tracking {
namespace {

std::vector<imu::ImuSample> constant_rate(const Eigen::Vector3d& w_B) {
  std::vector<imu::ImuSample> samples;
  for (int k = 0; k <= 200; ++k) {  // 1 s at 200 Hz
    imu::ImuSample s;
    s.stamp_ns = 1'000'000'000LL + k * 5'000'000LL;
    s.gyro_B = w_B;
    s.accel_B = Eigen::Vector3d(0, 0, 9.81);
    samples.push_back(s);
  }
  return samples;
}

const Eigen::Matrix3d kR_BC = geometry::so3_exp(Eigen::Vector3d(0.1, -1.2, 0.4));

TEST(GyroRotation, ConstantRateBetweenStampsOffTheImuGrid) {
  const Eigen::Vector3d w_B(0.3, -0.2, 0.5);  // rad/s
  const auto samples = constant_rate(w_B);
  const std::int64_t t0 = 1'123'456'789LL, t1 = t0 + 50'000'000LL;  // 50 ms, between IMU stamps
  const auto R = gyro_rotation_C(samples, t0, t1, kR_BC);
  ASSERT_TRUE(R.has_value());
  const Eigen::Matrix3d expected = kR_BC.transpose() * geometry::so3_exp(w_B * 0.05) * kR_BC;
  EXPECT_LT((*R - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(GyroRotation, BiasIsSubtracted) {
  const Eigen::Vector3d w_B(0.3, -0.2, 0.5);
  const auto R = gyro_rotation_C(constant_rate(w_B), 1'100'000'000LL, 1'150'000'000LL, kR_BC, w_B);
  ASSERT_TRUE(R.has_value());
  EXPECT_LT((*R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(GyroRotation, NoRotationWhenTheBufferDoesNotCoverTheInterval) {
  const auto samples = constant_rate(Eigen::Vector3d::Zero());
  EXPECT_FALSE(gyro_rotation_C(samples, 1'900'000'000LL, 2'100'000'000LL, kR_BC).has_value());  // ends at 2.0 s
  EXPECT_FALSE(gyro_rotation_C(samples, 900'000'000LL, 1'100'000'000LL, kR_BC).has_value());    // starts at 1.0 s
  EXPECT_FALSE(gyro_rotation_C(samples, 1'200'000'000LL, 1'200'000'000LL, kR_BC).has_value());  // empty interval
  EXPECT_FALSE(gyro_rotation_C({}, 1'200'000'000LL, 1'300'000'000LL, kR_BC).has_value());
}

}  // namespace
}  // namespace twinslam::tracking
