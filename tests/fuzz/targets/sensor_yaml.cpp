// EuRoC / Kalibr sensor.yaml: the camera's (intrinsics, distortion, T_BS) or the IMU's (noise densities).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/imu/imu_types.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  if (size == 0) return 0;
  const auto path = fuzz::write_scratch("sensor.yaml", data + 1, size - 1);
  return fuzz::expect_input_error_only([&] {
    if (data[0] % 2 == 0) read_camera_sensor_yaml(path);
    else imu::load_imu_noise(path);
  });
}
