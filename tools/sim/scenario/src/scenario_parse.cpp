// Scenario YAML -> Scenario: overlay of the file's keys on a base scenario, strict about keys and types. Range checks
// are in validate.cpp so that built-in scenarios go through the same checks.
#include <map>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "validate.hpp"
#include "yaml_reader.hpp"

namespace twinslam::sim {

namespace {

using detail::YamlReader;

void read_origin(const YamlReader& r, const YAML::Node& n, Origin& o) {
  r.expect_map(n, "origin");
  if (!n) return;
  r.check_keys(n, "origin.", {"lat", "lon", "alt"});
  r.read(n, "origin.", "lat", o.lat_deg);
  r.read(n, "origin.", "lon", o.lon_deg);
  r.read(n, "origin.", "alt", o.alt_m);
}

void read_optional_text(const YamlReader& r, const YAML::Node& map, const std::string& prefix, const char* name,
                        std::optional<std::string>& out) {
  const YAML::Node n = map[name];
  if (!n) return;
  if (n.IsNull()) {
    out.reset();
    return;
  }
  std::string v;
  r.read(map, prefix, name, v);
  out = v;
}

void read_city(const YamlReader& r, const YAML::Node& n, CityConfig& c) {
  r.expect_map(n, "city");
  if (!n) return;
  r.check_keys(n, "city.", {"source", "size_m", "height_m", "blocks", "path", "crs"});
  r.read(n, "city.", "source", c.source);
  r.read(n, "city.", "size_m", c.size_m);
  r.read(n, "city.", "height_m", c.height_m);
  r.read(n, "city.", "blocks", c.blocks);
  read_optional_text(r, n, "city.", "path", c.path);
  read_optional_text(r, n, "city.", "crs", c.crs);
}

void read_trajectory(const YamlReader& r, const YAML::Node& n, TrajectoryConfig& t) {
  r.expect_map(n, "trajectory");
  if (!n) return;
  r.check_keys(n, "trajectory.",
               {"type", "duration_s", "speed_mps", "altitude_m", "waypoints", "loops", "loop_rise_m"});
  r.read(n, "trajectory.", "type", t.type);
  r.read(n, "trajectory.", "duration_s", t.duration_s);
  r.read(n, "trajectory.", "speed_mps", t.speed_mps);
  r.read(n, "trajectory.", "altitude_m", t.altitude_m);
  r.read(n, "trajectory.", "loops", t.loops);
  r.read(n, "trajectory.", "loop_rise_m", t.loop_rise_m);
  if (const YAML::Node w = n["waypoints"]) {
    const std::string key = "trajectory.waypoints";
    r.record(key, w);
    if (!w.IsSequence()) r.fail(w, key, "expected a list of [east, north, up] points");
    t.waypoints_W.clear();
    for (const auto& p : w) {
      if (!p.IsSequence() || p.size() != 3) r.fail(p, key, "expected a point [east, north, up] in metres");
      t.waypoints_W.emplace_back(r.number(p[0], key), r.number(p[1], key), r.number(p[2], key));
    }
  }
}

void read_camera(const YamlReader& r, const YAML::Node& n, CameraSimConfig& c) {
  r.expect_map(n, "camera");
  if (!n) return;
  r.check_keys(n, "camera.", {"model", "width", "height", "rate_hz", "fov_deg", "T_BC",
                              "time_offset_s", "extrinsic_error_deg", "extrinsic_error_m", "auto_exposure_tau_s",
                              "intrinsic_error_focal", "intrinsic_error_px", "intrinsic_error_k1",
                              "line_time_us", "exposure_ms"});
  r.read(n, "camera.", "time_offset_s", c.time_offset_s);
  r.read(n, "camera.", "extrinsic_error_deg", c.extrinsic_error_deg);
  r.read(n, "camera.", "extrinsic_error_m", c.extrinsic_error_m);
  r.read(n, "camera.", "intrinsic_error_focal", c.intrinsic_error_focal);
  r.read(n, "camera.", "intrinsic_error_px", c.intrinsic_error_px);
  r.read(n, "camera.", "intrinsic_error_k1", c.intrinsic_error_k1);
  r.read(n, "camera.", "auto_exposure_tau_s", c.auto_exposure_tau_s);
  r.read(n, "camera.", "line_time_us", c.line_time_us);
  r.read(n, "camera.", "exposure_ms", c.exposure_ms);
  r.read(n, "camera.", "model", c.model);
  r.read(n, "camera.", "width", c.width);
  r.read(n, "camera.", "height", c.height);
  r.read(n, "camera.", "rate_hz", c.rate_hz);
  r.read(n, "camera.", "fov_deg", c.fov_deg);
  if (const YAML::Node t = n["T_BC"]) {
    if (t.IsNull()) {
      c.T_BC.reset();
      return;
    }
    std::array<double, 16> m{};
    r.read(n, "camera.", "T_BC", m);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m.data());
    c.T_BC = T;
  }
}

void read_imu(const YamlReader& r, const YAML::Node& n, ImuSimConfig& c) {
  r.expect_map(n, "imu");
  if (!n) return;
  r.check_keys(n, "imu.", {"rate_hz", "gyro_noise", "accel_noise", "gyro_walk", "accel_walk", "gyro_turn_on_bias",
                           "accel_turn_on_bias", "gyro_bias_instability", "accel_bias_instability", "bias_tau_s",
                           "gyro_scale_error", "accel_scale_error", "gyro_misalignment", "accel_misalignment"});
  r.read(n, "imu.", "rate_hz", c.rate_hz);
  r.read(n, "imu.", "gyro_noise", c.gyro_noise);
  r.read(n, "imu.", "accel_noise", c.accel_noise);
  r.read(n, "imu.", "gyro_walk", c.gyro_walk);
  r.read(n, "imu.", "accel_walk", c.accel_walk);
  r.read(n, "imu.", "gyro_turn_on_bias", c.gyro_turn_on_bias);
  r.read(n, "imu.", "accel_turn_on_bias", c.accel_turn_on_bias);
  r.read(n, "imu.", "gyro_bias_instability", c.gyro_bias_instability);
  r.read(n, "imu.", "accel_bias_instability", c.accel_bias_instability);
  r.read(n, "imu.", "bias_tau_s", c.bias_tau_s);
  r.read(n, "imu.", "gyro_scale_error", c.gyro_scale_error);
  r.read(n, "imu.", "accel_scale_error", c.accel_scale_error);
  r.read(n, "imu.", "gyro_misalignment", c.gyro_misalignment);
  r.read(n, "imu.", "accel_misalignment", c.accel_misalignment);
}

void read_gnss(const YamlReader& r, const YAML::Node& n, GnssSimConfig& c) {
  r.expect_map(n, "gnss");
  if (!n) return;
  r.check_keys(n, "gnss.", {"rate_hz", "model", "sigma_m"});
  r.read(n, "gnss.", "rate_hz", c.rate_hz);
  r.read(n, "gnss.", "model", c.model);
  r.read(n, "gnss.", "sigma_m", c.sigma_m);
}

void read_traffic(const YamlReader& r, const YAML::Node& n, TrafficSimConfig& c) {
  r.expect_map(n, "traffic");
  if (!n) return;
  r.check_keys(n, "traffic.", {"cars", "speed_mps"});
  r.read(n, "traffic.", "cars", c.cars);
  r.read(n, "traffic.", "speed_mps", c.speed_mps);
}

void read_shifted_buildings(const YamlReader& r, const YAML::Node& n, ShiftedBuildings& c) {
  r.expect_map(n, "twin.shifted_buildings");
  if (!n) return;
  r.check_keys(n, "twin.shifted_buildings.", {"count", "offset_m"});
  r.read(n, "twin.shifted_buildings.", "count", c.count);
  r.read(n, "twin.shifted_buildings.", "offset_m", c.offset_m);
}

void read_twin(const YamlReader& r, const YAML::Node& n, TwinConfig& c) {
  r.expect_map(n, "twin");
  if (!n) return;
  r.check_keys(n, "twin.", {"noise_m", "missing_buildings", "added_buildings", "offset_m", "shifted_buildings"});
  r.read(n, "twin.", "noise_m", c.noise_m);
  r.read(n, "twin.", "missing_buildings", c.missing_buildings);
  r.read(n, "twin.", "added_buildings", c.added_buildings);
  std::array<double, 3> off{c.offset_m.x(), c.offset_m.y(), c.offset_m.z()};
  r.read(n, "twin.", "offset_m", off);
  c.offset_m = Eigen::Vector3d(off[0], off[1], off[2]);
  read_shifted_buildings(r, n["shifted_buildings"], c.shifted_buildings);
}

}  // namespace

Scenario parse_scenario_yaml(const std::string& text, const std::string& file, const Scenario& base) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, e.mark.line >= 0 ? static_cast<std::size_t>(e.mark.line) + 1 : 0,
                           "malformed YAML: " + e.msg));
  }
  if (!root || root.IsNull()) throw InputError(where(file, 0, "empty scenario file"));
  std::map<std::string, std::size_t> lines;
  const YamlReader r(file, lines);
  if (!root.IsMap()) r.fail(root, "(top level)", "expected a mapping of keys");
  r.check_keys(root, "", {"name", "base", "seed", "origin", "city", "trajectory", "camera", "imu", "gnss", "twin",
                         "traffic"});

  Scenario s = base;
  if (const YAML::Node b = root["base"]) {
    std::string name;
    r.read(root, "", "base", name);
    try {
      s = builtin_scenario(name);
    } catch (const UsageError& e) {
      r.fail(b, "base", e.what());
    }
    s.name = file;
  }
  r.read(root, "", "name", s.name);
  r.read(root, "", "seed", s.seed);
  read_origin(r, root["origin"], s.origin);
  if (root["origin"]) s.origin_given = true;
  read_city(r, root["city"], s.city);
  read_imu(r, root["imu"], s.imu);
  read_gnss(r, root["gnss"], s.gnss);
  read_twin(r, root["twin"], s.twin);
  read_traffic(r, root["traffic"], s.traffic);

  // Without camera.T_BC in the file, a base whose extrinsics were the default of its trajectory type gets the default of
  // the (possibly changed) type, so `base: city-loops` with `type: survey` looks down-forward like any survey.
  const std::string base_type = s.trajectory.type;
  const bool base_default = !s.camera.T_BC || s.camera.T_BC->isApprox(default_T_BC(base_type), 0.0);
  read_trajectory(r, root["trajectory"], s.trajectory);
  read_camera(r, root["camera"], s.camera);
  const YAML::Node cam = root["camera"];
  const bool given = cam && cam.IsMap() && cam["T_BC"] && !cam["T_BC"].IsNull();
  if (!given && base_default) s.camera.T_BC.reset();

  detail::validate_scenario_at(s, file, lines);
  if (!s.camera.T_BC) s.camera.T_BC = default_T_BC(s.trajectory.type);
  return s;
}

}  // namespace twinslam::sim
