// Built-in scenarios, `--scenario NAME|FILE.yaml` resolution and the default camera extrinsics.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "validate.hpp"

namespace twinslam::sim {

std::vector<std::string> builtin_scenario_names() { return {"tiny", "city-loops", "city-survey", "city-long"}; }

Eigen::Isometry3d default_T_BC(const std::string& trajectory_type) {
  // Camera axes in B (x forward, y left, z up): optical axis z_C pitched `down` below body x, x_C = -y_B (image right),
  // y_C = z_C x x_C (image down).
  const double down = trajectory_type == "survey" ? 45.0 * M_PI / 180.0 : 0.0;  // [rad]
  const Eigen::Vector3d z_C(std::cos(down), 0, -std::sin(down));
  const Eigen::Vector3d x_C(0, -1, 0);
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear().col(0) = x_C;
  T_BC.linear().col(1) = z_C.cross(x_C);
  T_BC.linear().col(2) = z_C;
  T_BC.translation() = Eigen::Vector3d(0.10, 0.0, -0.05);  // [m, B]
  return T_BC;
}

Eigen::Isometry3d camera_T_BC(const Scenario& scenario) {
  return scenario.camera.T_BC ? *scenario.camera.T_BC : default_T_BC(scenario.trajectory.type);
}

Scenario builtin_scenario(const std::string& name) {
  Scenario s;  // struct defaults = the CONTRACTS.md example
  s.name = name;
  if (name == "tiny") {
    // About 30 s over a 200 m city: light enough that `twinslam sim --scenario tiny` finishes in <= 60 s.
    s.city.size_m = 200;
    s.city.height_m = {8, 30};
    s.trajectory.duration_s = 30;
    s.trajectory.speed_mps = 3.0;
    s.trajectory.altitude_m = {2, 12};
    s.trajectory.loops = 1;
    // Ideal sensors, so the tests built on `tiny` see exactly what they always saw.
    s.camera.time_offset_s = s.camera.extrinsic_error_deg = s.camera.extrinsic_error_m = 0;
    s.camera.intrinsic_error_focal = s.camera.intrinsic_error_px = s.camera.intrinsic_error_k1 = 0;
    s.camera.auto_exposure_tau_s = 0;
    s.camera.line_time_us = s.camera.exposure_ms = 0;
    s.traffic.cars = 0;
    ImuSimConfig& imu = s.imu;
    imu.gyro_turn_on_bias = imu.accel_turn_on_bias = imu.gyro_bias_instability = imu.accel_bias_instability = 0;
    imu.bias_tau_s = imu.gyro_scale_error = imu.accel_scale_error = imu.gyro_misalignment = imu.accel_misalignment = 0;
  } else if (name == "city-loops") {
    // Three loops around the tallest building, about 500 m in 5 min (1.7 m/s over 296 s of cruise).
    s.trajectory.speed_mps = 1.7;
  } else if (name == "city-survey") {
    // About 500 m of lawnmower lanes over the blocks, above the tallest building (60 m).
    s.trajectory.type = "survey";
    s.trajectory.speed_mps = 1.7;
    s.trajectory.altitude_m = {68, 75};
  } else if (name == "city-long") {
    // 2.33 km through the streets in 13 min (3 m/s over 776 s of cruise), 15-35 m above ground (the street trees
    // reach 10 m), with a 180 m stretch close along one facade row, a diagonal across a park, and a twin that is
    // wrong about a few of the buildings along the route. The default 600 m city (the world of city-loops) holds
    // the route without flying a street twice (about 40 of its 64 inner intersections), and keeps the density of
    // the 20 000 ideal-track landmarks of `sim --features`, which are spread over the whole city.
    s.trajectory.type = "streets";
    s.trajectory.duration_s = 780;
    s.trajectory.speed_mps = 3.0;
    s.trajectory.altitude_m = {15, 35};
    s.twin.missing_buildings = 3;
    s.twin.shifted_buildings = {3, 4.0};
  } else {
    std::string list;
    for (const auto& n : builtin_scenario_names()) list += (list.empty() ? "" : ", ") + n;
    throw UsageError("unknown scenario '" + name + "' (built-in: " + list + "; or give a .yaml file)");
  }
  s.camera.T_BC = default_T_BC(s.trajectory.type);
  validate_scenario(s, "scenario " + name);
  return s;
}

Scenario load_scenario(const std::string& name_or_file) {
  for (const auto& n : builtin_scenario_names())
    if (n == name_or_file) return builtin_scenario(n);
  std::ifstream in(name_or_file);
  if (!in) {
    std::string list;
    for (const auto& n : builtin_scenario_names()) list += (list.empty() ? "" : ", ") + n;
    throw InputError(where(name_or_file, 0, "cannot open scenario file (built-in: " + list + ")"));
  }
  std::stringstream text;
  text << in.rdbuf();
  Scenario base;
  base.name = name_or_file;
  Scenario s = parse_scenario_yaml(text.str(), name_or_file, base);
  // A relative city.path is relative to the scenario file's folder (made absolute, so dataset.yaml's echo reads back
  // from anywhere).
  if (s.city.path && !s.city.path->empty() && std::filesystem::path(*s.city.path).is_relative())
    s.city.path = std::filesystem::absolute(std::filesystem::path(name_or_file).parent_path() / *s.city.path)
                      .lexically_normal()
                      .string();
  return s;
}

}  // namespace twinslam::sim
