// The tracking service's frame handler (tracking_handler.hpp), the part of the service that sees every DDS sample:
// bad samples are refused and counted, never the end of the service.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "tracking_handler.hpp"

namespace twinslam::tracking {
namespace {

constexpr int kWidth = 160, kHeight = 100;
constexpr std::int64_t kFrame_ns = 50'000'000, kImu_ns = 5'000'000;

TrackingNodeOptions small_camera() {
  TrackingNodeOptions o;
  o.camera.intrinsics.width = kWidth;
  o.camera.intrinsics.height = kHeight;
  o.camera.intrinsics.fu = o.camera.intrinsics.fv = 100.0;
  o.camera.intrinsics.cu = 79.5;
  o.camera.intrinsics.cv = 49.5;
  return o;
}

msg::Image textured(std::int64_t stamp_ns, int shift_px) {
  msg::Image m;
  m.vehicle_id("uav1");
  m.stamp_ns(stamp_ns);
  m.encoding("mono8");
  m.width(kWidth);
  m.height(kHeight);
  m.step(kWidth);
  m.data().resize(static_cast<std::size_t>(kWidth) * kHeight);
  for (int v = 0; v < kHeight; ++v)
    for (int u = 0; u < kWidth; ++u) {
      const int x = u + shift_px;
      m.data()[static_cast<std::size_t>(v * kWidth + u)] =
          static_cast<std::uint8_t>(127 + 120 * std::sin(0.3 * x) * std::cos(0.23 * v + 0.1 * x));
    }
  return m;
}

std::vector<imu::ImuSample> imu_between(std::int64_t from_ns, std::int64_t to_ns, double gyro_z) {
  std::vector<imu::ImuSample> out;
  for (std::int64_t t = from_ns; t < to_ns; t += kImu_ns)
    out.push_back({t, Eigen::Vector3d(0, 0, gyro_z), Eigen::Vector3d(0, 0, 9.81)});
  return out;
}

// A NaN gyro sample used to reach the gyro prediction, which threw on the worker thread and ended the service
// (found by fuzz_dds_tracking; its input is tests/fuzz/corpus/dds_tracking/regression-nonfinite-imu).
TEST(TrackingHandler, NonFiniteAndImpossibleImuSamplesAreRefusedAndTrackingGoesOn) {
  dds::Counters counters;
  TrackingHandler handler(counters, small_camera());
  const std::int64_t t0 = 1'000'000'000;
  int frames_out = 0;
  for (int k = 0; k < 6; ++k) {
    const std::int64_t t = t0 + k * kFrame_ns;
    auto imu = imu_between(t - kFrame_ns + kImu_ns, t + kImu_ns, 0.0);
    if (k == 2) imu[3].gyro_B.x() = std::numeric_limits<double>::quiet_NaN();
    if (k == 3) imu[1].accel_B.z() = std::numeric_limits<double>::infinity();
    if (k == 4) imu[5].gyro_B.z() = 1e6;  // rad/s: no gyro measures that
    const auto out = handler.handle(textured(t, k), std::move(imu));
    ASSERT_TRUE(out.has_value()) << "frame " << k;
    frames_out += !out->features().empty();
  }
  EXPECT_EQ(counters.get("imu_rejected"), 3u);
  EXPECT_EQ(counters.get("images_rejected"), 0u);
  EXPECT_GE(frames_out, 5);
}

TEST(TrackingHandler, ImagesThatDoNotMatchTheCameraAreSkippedAndCounted) {
  dds::Counters counters;
  TrackingHandler handler(counters, small_camera());
  msg::Image wrong_size = textured(1'000'000'000, 0);
  wrong_size.width(kWidth + (1u << 31));  // beyond int: must not wrap into the camera's width
  EXPECT_FALSE(handler.handle(wrong_size, {}).has_value());
  msg::Image short_data = textured(1'050'000'000, 0);
  short_data.data().resize(100);
  EXPECT_FALSE(handler.handle(short_data, {}).has_value());
  msg::Image colour = textured(1'100'000'000, 0);
  colour.encoding("rgb8");
  EXPECT_FALSE(handler.handle(colour, {}).has_value());
  EXPECT_EQ(counters.get("images_rejected"), 3u);
  EXPECT_TRUE(handler.handle(textured(1'150'000'000, 0), {}).has_value());
}

}  // namespace
}  // namespace twinslam::tracking
