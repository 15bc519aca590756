// Scenario -> YAML with every key, numbers in shortest round-trip form, so dataset.yaml records exactly what was run.
#include <charconv>
#include <sstream>

#include "twinslam/sim/scenario_io.hpp"

namespace twinslam::sim {

namespace {

std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// YAML double-quoted scalar: escapes backslash and quote (paths may hold anything).
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

template <typename Seq>
std::string list(const Seq& values) {
  std::string out = "[";
  for (const double v : values) out += (out.size() > 1 ? ", " : "") + num(v);
  return out + "]";
}

}  // namespace

std::string scenario_to_yaml(const Scenario& s) {
  std::ostringstream o;
  o << "name: " << quoted(s.name) << "\n";
  o << "seed: " << s.seed << "\n";
  o << "origin: {lat: " << num(s.origin.lat_deg) << ", lon: " << num(s.origin.lon_deg) << ", alt: " << num(s.origin.alt_m)
    << "}\n";
  o << "city:\n  source: " << s.city.source << "\n  size_m: " << num(s.city.size_m) << "\n  height_m: "
    << list(s.city.height_m) << "\n  blocks: " << s.city.blocks
    << "\n  path: " << (s.city.path ? quoted(*s.city.path) : "null")
    << "\n  crs: " << (s.city.crs ? quoted(*s.city.crs) : "null") << "\n";
  const TrajectoryConfig& t = s.trajectory;
  o << "trajectory:\n  type: " << t.type << "\n  duration_s: " << num(t.duration_s) << "\n  speed_mps: "
    << num(t.speed_mps) << "\n  altitude_m: " << list(t.altitude_m) << "\n  loops: " << num(t.loops)
    << "\n  loop_rise_m: " << num(t.loop_rise_m) << "\n  waypoints: [";
  for (std::size_t i = 0; i < t.waypoints_W.size(); ++i)
    o << (i ? ", " : "") << list(std::array<double, 3>{t.waypoints_W[i].x(), t.waypoints_W[i].y(), t.waypoints_W[i].z()});
  o << "]\n";
  const Eigen::Matrix4d T = camera_T_BC(s).matrix();
  std::array<double, 16> T_rows{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T_rows[static_cast<std::size_t>(4 * r + c)] = T(r, c);
  o << "camera:\n  model: " << s.camera.model << "\n  width: " << s.camera.width << "\n  height: " << s.camera.height
    << "\n  rate_hz: " << num(s.camera.rate_hz) << "\n  fov_deg: " << num(s.camera.fov_deg)
    << "\n  T_BC: " << list(T_rows) << "   # body <- camera, row-major 4x4\n";
  o << "  time_offset_s: " << num(s.camera.time_offset_s) << "\n  extrinsic_error_deg: "
    << num(s.camera.extrinsic_error_deg) << "\n  extrinsic_error_m: " << num(s.camera.extrinsic_error_m)
    << "\n  intrinsic_error_focal: " << num(s.camera.intrinsic_error_focal)
    << "\n  intrinsic_error_px: " << num(s.camera.intrinsic_error_px)
    << "\n  intrinsic_error_k1: " << num(s.camera.intrinsic_error_k1)
    << "\n  auto_exposure_tau_s: " << num(s.camera.auto_exposure_tau_s)
    << "\n  line_time_us: " << num(s.camera.line_time_us) << "\n  exposure_ms: " << num(s.camera.exposure_ms) << "\n";
  o << "imu: {rate_hz: " << num(s.imu.rate_hz) << ", gyro_noise: " << num(s.imu.gyro_noise)
    << ", accel_noise: " << num(s.imu.accel_noise) << ", gyro_walk: " << num(s.imu.gyro_walk)
    << ", accel_walk: " << num(s.imu.accel_walk) << ",\n      gyro_turn_on_bias: " << num(s.imu.gyro_turn_on_bias)
    << ", accel_turn_on_bias: " << num(s.imu.accel_turn_on_bias)
    << ", gyro_bias_instability: " << num(s.imu.gyro_bias_instability)
    << ", accel_bias_instability: " << num(s.imu.accel_bias_instability) << ", bias_tau_s: " << num(s.imu.bias_tau_s)
    << ",\n      gyro_scale_error: " << num(s.imu.gyro_scale_error)
    << ", accel_scale_error: " << num(s.imu.accel_scale_error)
    << ", gyro_misalignment: " << num(s.imu.gyro_misalignment)
    << ", accel_misalignment: " << num(s.imu.accel_misalignment) << "}\n";
  o << "gnss: {rate_hz: " << num(s.gnss.rate_hz) << ", model: " << s.gnss.model << ", sigma_m: " << num(s.gnss.sigma_m)
    << "}\n";
  o << "twin: {noise_m: " << num(s.twin.noise_m) << ", missing_buildings: " << s.twin.missing_buildings
    << ", added_buildings: " << s.twin.added_buildings << ", offset_m: "
    << list(std::array<double, 3>{s.twin.offset_m.x(), s.twin.offset_m.y(), s.twin.offset_m.z()})
    << ", shifted_buildings: {count: " << s.twin.shifted_buildings.count
    << ", offset_m: " << num(s.twin.shifted_buildings.offset_m) << "}}\n";
  o << "traffic: {cars: " << s.traffic.cars << ", speed_mps: " << num(s.traffic.speed_mps) << "}\n";
  return o.str();
}

}  // namespace twinslam::sim
