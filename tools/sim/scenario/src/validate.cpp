// Range and consistency checks of every scenario key, in one place (built-ins and files go through the same checks).
#include "validate.hpp"

#include <cmath>
#include <set>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/scenario_io.hpp"

namespace twinslam::sim {
namespace detail {

namespace {

class Checker {
 public:
  Checker(const std::string& file, const std::map<std::string, std::size_t>& lines) : file_(file), lines_(lines) {}

  void require(bool ok, const std::string& key, const std::string& what) const {
    if (ok) return;
    const auto it = lines_.find(key);
    throw InputError(where(file_, it == lines_.end() ? 0 : it->second, key + ": " + what));
  }
  void positive(double v, const std::string& key) const { require(v > 0, key, "must be > 0"); }
  void non_negative(double v, const std::string& key) const { require(v >= 0, key, "must be >= 0"); }
  // An imperfection's size: 0 (off) up to hi; negative and NaN refused.
  void magnitude(double v, double hi, const std::string& key, const std::string& unit) const {
    require(v >= 0 && v <= hi, key, "must be in [0, " + fmt(hi) + "] " + unit + " (0 turns it off)");
  }
  void in_range(double v, double lo, double hi, const std::string& key) const {
    require(v >= lo && v <= hi, key, "must be in [" + fmt(lo) + ", " + fmt(hi) + "]");
  }
  void one_of(const std::string& v, const std::set<std::string>& allowed, const std::string& key) const {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : " | ") + a;
    require(allowed.count(v) > 0, key, "'" + v + "' is not one of " + list);
  }

 private:
  static std::string fmt(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }
  const std::string& file_;
  const std::map<std::string, std::size_t>& lines_;
};

void check_T_BC(const Checker& c, const Eigen::Isometry3d& T) {
  const Eigen::Matrix4d& m = T.matrix();
  c.require(m.allFinite(), "camera.T_BC", "must be finite");
  c.require(m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12), "camera.T_BC", "last row must be 0 0 0 1");
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  c.require((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-6 && R.determinant() > 0, "camera.T_BC",
            "rotation part must be orthonormal with determinant +1");
}

}  // namespace

void validate_scenario_at(const Scenario& s, const std::string& file, const std::map<std::string, std::size_t>& lines) {
  const Checker c(file, lines);
  c.in_range(s.origin.lat_deg, -90, 90, "origin.lat");
  c.in_range(s.origin.lon_deg, -180, 180, "origin.lon");
  c.in_range(s.origin.alt_m, -1000, 10000, "origin.alt");

  c.one_of(s.city.source, {"procedural", "osm", "cityjson", "mesh", "3dtiles"}, "city.source");
  c.in_range(s.city.size_m, 50, 10000, "city.size_m");
  c.positive(s.city.height_m[0], "city.height_m");
  c.require(s.city.height_m[1] >= s.city.height_m[0] && s.city.height_m[1] <= 1000, "city.height_m",
            "must be [min, max] with min <= max <= 1000");
  c.one_of(s.city.blocks, {"varied", "identical"}, "city.blocks");
  c.require(s.city.blocks == "varied" || s.city.source == "procedural", "city.blocks",
            "identical blocks need the procedural city");
  c.require(s.city.source == "procedural" || (s.city.path && !s.city.path->empty()), "city.path",
            "required when city.source is " + s.city.source);
  if (s.city.crs) c.require(s.city.crs->rfind("EPSG:", 0) == 0, "city.crs", "must look like EPSG:nnnn");

  const TrajectoryConfig& t = s.trajectory;
  c.one_of(t.type, {"loops", "survey", "waypoints", "streets"}, "trajectory.type");
  c.in_range(t.duration_s, 10, 36000, "trajectory.duration_s");
  c.require(t.speed_mps > 0 && t.speed_mps <= 15, "trajectory.speed_mps", "must be > 0 and <= 15");
  c.require(t.altitude_m[0] >= 0.5 && t.altitude_m[1] >= t.altitude_m[0] && t.altitude_m[1] <= 500,
            "trajectory.altitude_m", "must be [min, max] with 0.5 <= min <= max <= 500");
  c.require(t.loops > 0 && t.loops <= 20, "trajectory.loops", "must be > 0 and <= 20");
  c.in_range(t.loop_rise_m, 0, 50, "trajectory.loop_rise_m");
  if (t.type == "waypoints")
    c.require(t.waypoints_W.size() >= 2, "trajectory.waypoints", "type waypoints needs at least 2 points");
  if (t.type == "streets")
    c.require(s.city.source == "procedural", "trajectory.type", "streets needs the procedural city's street grid");
  if (t.type == "survey" && s.city.source == "procedural")
    c.require(t.altitude_m[0] >= s.city.height_m[1] + 5, "trajectory.altitude_m",
              "a survey flies over the blocks: min must be >= city.height_m max + 5");

  c.one_of(s.camera.model, {"fisheye-equidistant", "pinhole-radtan"}, "camera.model");
  c.require(s.camera.width >= 16 && s.camera.width <= 8192, "camera.width", "must be in [16, 8192]");
  c.require(s.camera.height >= 16 && s.camera.height <= 8192, "camera.height", "must be in [16, 8192]");
  c.require(s.camera.rate_hz > 0 && s.camera.rate_hz <= 1000, "camera.rate_hz", "must be > 0 and <= 1000");
  const double max_fov = s.camera.model == "pinhole-radtan" ? 150 : 200;
  c.require(s.camera.fov_deg > 0 && s.camera.fov_deg <= max_fov, "camera.fov_deg",
            "must be > 0 and <= " + std::to_string(static_cast<int>(max_fov)) + " for " + s.camera.model);
  if (s.camera.T_BC) check_T_BC(c, *s.camera.T_BC);
  c.require(std::abs(s.camera.time_offset_s) <= 0.1, "camera.time_offset_s",
            "must be in [-0.1, 0.1] s (0 turns it off)");  // also refuses NaN
  c.magnitude(s.camera.extrinsic_error_deg, 10, "camera.extrinsic_error_deg", "deg");
  c.magnitude(s.camera.extrinsic_error_m, 0.5, "camera.extrinsic_error_m", "m");
  c.magnitude(s.camera.intrinsic_error_focal, 0.05, "camera.intrinsic_error_focal", "(relative)");
  c.magnitude(s.camera.intrinsic_error_px, 20, "camera.intrinsic_error_px", "px");
  c.magnitude(s.camera.intrinsic_error_k1, 0.05, "camera.intrinsic_error_k1", "(coefficient)");
  c.magnitude(s.camera.auto_exposure_tau_s, 60, "camera.auto_exposure_tau_s", "s");
  // A row's readout and a frame's exposure both fit in the frame period.
  const double frame_us = 1e6 / s.camera.rate_hz;
  c.require(s.camera.line_time_us >= 0 && s.camera.line_time_us * s.camera.height <= frame_us, "camera.line_time_us",
            "must be >= 0 with line_time_us x height within a frame period (1e6 / rate_hz us) (0 turns it off)");
  c.require(s.camera.exposure_ms >= 0 && s.camera.exposure_ms <= frame_us / 1000, "camera.exposure_ms",
            "must be >= 0 and at most a frame period (1000 / rate_hz ms) (0 turns it off)");

  c.require(s.imu.rate_hz > 0 && s.imu.rate_hz <= 10000, "imu.rate_hz", "must be > 0 and <= 10000");
  c.non_negative(s.imu.gyro_noise, "imu.gyro_noise");
  c.non_negative(s.imu.accel_noise, "imu.accel_noise");
  c.non_negative(s.imu.gyro_walk, "imu.gyro_walk");
  c.non_negative(s.imu.accel_walk, "imu.accel_walk");
  c.magnitude(s.imu.gyro_turn_on_bias, 1, "imu.gyro_turn_on_bias", "rad/s");
  c.magnitude(s.imu.accel_turn_on_bias, 2, "imu.accel_turn_on_bias", "m/s^2");
  c.magnitude(s.imu.gyro_bias_instability, 0.1, "imu.gyro_bias_instability", "rad/s");
  c.magnitude(s.imu.accel_bias_instability, 1, "imu.accel_bias_instability", "m/s^2");
  c.magnitude(s.imu.bias_tau_s, 1e5, "imu.bias_tau_s", "s");
  c.magnitude(s.imu.gyro_scale_error, 0.2, "imu.gyro_scale_error", "(fraction)");
  c.magnitude(s.imu.accel_scale_error, 0.2, "imu.accel_scale_error", "(fraction)");
  c.magnitude(s.imu.gyro_misalignment, 0.2, "imu.gyro_misalignment", "rad");
  c.magnitude(s.imu.accel_misalignment, 0.2, "imu.accel_misalignment", "rad");

  c.require(s.gnss.rate_hz > 0 && s.gnss.rate_hz <= 100, "gnss.rate_hz", "must be > 0 and <= 100");
  c.one_of(s.gnss.model, {"raytrace", "learned", "gaussian"}, "gnss.model");
  c.require(s.gnss.sigma_m > 0 && s.gnss.sigma_m <= 100, "gnss.sigma_m", "must be > 0 and <= 100");

  c.require(s.traffic.cars >= 0 && s.traffic.cars <= 10000, "traffic.cars", "must be in [0, 10000] (0 turns it off)");
  c.magnitude(s.traffic.speed_mps, 40, "traffic.speed_mps", "m/s (0: the cars stand still)");

  c.non_negative(s.twin.noise_m, "twin.noise_m");
  c.require(s.twin.missing_buildings >= 0, "twin.missing_buildings", "must be >= 0");
  c.require(s.twin.added_buildings >= 0, "twin.added_buildings", "must be >= 0");
  c.require(s.twin.offset_m.allFinite() && s.twin.offset_m.norm() <= 1000, "twin.offset_m",
            "must be finite and shorter than 1000 m");
  // The upper bound of the count depends on the city (buildings - 1 - missing): derive_twin checks it.
  c.require(s.twin.shifted_buildings.count >= 0, "twin.shifted_buildings.count", "must be >= 0");
  c.require(std::isfinite(s.twin.shifted_buildings.offset_m) && s.twin.shifted_buildings.offset_m >= 0 &&
                s.twin.shifted_buildings.offset_m <= kMaxBuildingShift_m,
            "twin.shifted_buildings.offset_m", "must be in [0, " + std::to_string(int(kMaxBuildingShift_m)) + "] m");
}

}  // namespace detail

void validate_scenario(const Scenario& scenario, const std::string& file) {
  detail::validate_scenario_at(scenario, file, {});
}

}  // namespace twinslam::sim
