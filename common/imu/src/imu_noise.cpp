#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"
#include "twinslam/imu/imu_types.hpp"

namespace twinslam::imu {

void ImuNoise::validate() const {
  const std::pair<const char*, double> fields[] = {
      {"gyroscope_noise_density", gyroscope_noise_density},
      {"gyroscope_random_walk", gyroscope_random_walk},
      {"accelerometer_noise_density", accelerometer_noise_density},
      {"accelerometer_random_walk", accelerometer_random_walk},
      {"rate_hz", rate_hz},
  };
  for (const auto& [name, value] : fields) {
    // Zero noise would make the preintegrated covariance singular and the factor weight infinite.
    if (!std::isfinite(value) || value <= 0.0) {
      throw InputError(std::string("IMU noise: ") + name + " must be finite and > 0, got " + std::to_string(value));
    }
  }
}

ImuNoise load_imu_noise(const std::filesystem::path& sensor_yaml) {
  const std::string file = sensor_yaml.string();
  std::ifstream in(sensor_yaml);
  if (!in) throw InputError(where(file, 0, "cannot open file"));
  std::stringstream text;
  text << in.rdbuf();
  std::string content = text.str();
  // EuRoC files start with OpenCV's "%YAML:1.0", which is not a valid YAML directive: blank that line out (keeping
  // line numbers) before parsing.
  if (content.rfind("%YAML", 0) == 0) content.replace(0, content.find('\n'), "");

  YAML::Node root;
  try {
    root = YAML::Load(content);
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg));
  }
  if (!root.IsMap()) throw InputError(where(file, 0, "expected a YAML mapping"));

  auto read = [&](const char* key) {
    const YAML::Node node = root[key];
    if (!node) throw InputError(where(file, 0, std::string("missing key ") + key));
    try {
      return node.as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(where(file, static_cast<std::size_t>(node.Mark().line + 1),
                             std::string(key) + " is not a number"));
    }
  };
  ImuNoise noise;
  noise.gyroscope_noise_density = read("gyroscope_noise_density");
  noise.gyroscope_random_walk = read("gyroscope_random_walk");
  noise.accelerometer_noise_density = read("accelerometer_noise_density");
  noise.accelerometer_random_walk = read("accelerometer_random_walk");
  noise.rate_hz = read("rate_hz");
  try {
    noise.validate();
  } catch (const InputError& e) {
    throw InputError(where(file, 0, e.what()));
  }
  return noise;
}

}  // namespace twinslam::imu
