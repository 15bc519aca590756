// loops | survey | waypoints | streets: a planar path (path.hpp) sampled at constant spacing into the control points
// of a quintic B-spline that starts and ends at rest (five equal control points at each end make all derivatives up
// to the fourth vanish there).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "path.hpp"
#include "street_route.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/sim/flight_limits.hpp"
#include "twinslam/sim/flight_trajectory.hpp"

namespace twinslam::sim {

namespace {

using detail::PlanarPath;

constexpr double kKnotSpacing = 1.0;         // [s] about one control point per second of flight
constexpr double kLoopHeadingOffset = M_PI / 4;  // loops: body x turned 45 deg from the direction of travel inward
constexpr double kFilletRadius = 8.0;        // [m] corner radius of survey lanes and waypoint paths
constexpr double kSurveyLaneSpacing = 40.0;  // [m]

// Zig-zag added to control points 1..8 (lateral [m], vertical [m], yaw [rad]): uneven periods so that the spline
// (a low-pass filter) keeps enough of it to excite every accelerometer and gyroscope axis during initialization.
Eigen::Vector3d excitation(std::size_t j) {
  if (j == 0 || j > 8) return Eigen::Vector3d::Zero();
  const double x = static_cast<double>(j);
  const double taper = j <= 5 ? 1.0 : (9.0 - x) / 4.0;
  return taper * Eigen::Vector3d(1.2 * std::sin(M_PI * x / 2), 0.8 * std::sin(2 * M_PI * x / 3),
                                 0.35 * std::sin(M_PI * x / 2 + 1.0));
}

// Samples `path` over its first `fly_length` [m] into a spline of exactly duration_s: the drone flies at about
// speed_mps and then hovers at the end if time remains.
FlightTrajectory sample_path(const PlanarPath& path, double fly_length, double heading_offset,
                             const TrajectoryConfig& cfg, const std::string& what) {
  const auto segments = static_cast<std::size_t>(std::max(10.0, std::round(cfg.duration_s / kKnotSpacing)));
  const double dt = cfg.duration_s / static_cast<double>(segments);
  const std::size_t samples = segments - 3;  // + 4 copies at each end = segments + 5 control points
  const auto moving = static_cast<std::size_t>(std::max(1.0, std::ceil(fly_length / (cfg.speed_mps * dt) - 1e-9)));
  if (moving > samples - 1) {
    std::ostringstream m;
    m << "trajectory.duration_s: the path is " << fly_length << " m, which needs "
      << (static_cast<double>(moving) + 4) * dt << " s at trajectory.speed_mps";
    throw InputError(where(what, 0, m.str()));
  }
  std::vector<Eigen::Vector4d> cps;
  double previous_yaw = 0;
  for (std::size_t j = 0; j < samples; ++j) {
    const double s = fly_length * static_cast<double>(std::min(j, moving)) / static_cast<double>(moving);
    const detail::PathPoint p = path.at(s);
    double yaw = p.heading + heading_offset;
    if (j > 0) yaw = previous_yaw + std::remainder(yaw - previous_yaw, 2 * M_PI);  // unwrap
    previous_yaw = yaw;
    const Eigen::Vector3d e = excitation(j);
    const Eigen::Vector3d left(-std::sin(p.heading), std::cos(p.heading), 0);
    const Eigen::Vector3d pos = p.p_W + e.x() * left + Eigen::Vector3d(0, 0, e.y());
    const Eigen::Vector4d c(pos.x(), pos.y(), pos.z(), yaw + e.z());
    if (j == 0) cps.insert(cps.end(), 4, c);
    cps.push_back(c);
  }
  cps.insert(cps.end(), 4, cps.back());
  return FlightTrajectory(QuinticBSpline(std::move(cps), dt));
}

double cruise_length(const TrajectoryConfig& cfg) {
  const double segments = std::max(10.0, std::round(cfg.duration_s / kKnotSpacing));
  return cfg.speed_mps * cfg.duration_s * (segments - 4) / segments;  // 4 knot intervals of start-up and stop
}

FlightTrajectory make_loops(const Scenario& sc, const SceneHints& hints) {
  const LoopsGeometry g = loops_geometry(sc, hints);
  PlanarPath path;  // counter-clockwise from the south side: the building is on the left
  path.add_arc(g.center_W, g.radius_m, -M_PI / 2, 2 * M_PI * g.turns, g.z_start_m, g.z_start_m + g.rise_m);
  return sample_path(path, cruise_length(sc.trajectory), kLoopHeadingOffset, sc.trajectory, sc.name);
}

FlightTrajectory make_survey(const Scenario& sc, const SceneHints& hints) {
  const TrajectoryConfig& cfg = sc.trajectory;
  const double length = cruise_length(cfg);
  const auto& ext = hints.extent_W;
  const Eigen::Vector2d center(0.5 * (ext[0] + ext[2]), 0.5 * (ext[1] + ext[3]));
  const double lane = std::clamp(0.5 * std::min(ext[2] - ext[0], ext[3] - ext[1]), 40.0, 150.0);
  const auto lanes = static_cast<int>(std::ceil((length + kSurveyLaneSpacing) / (lane + kSurveyLaneSpacing))) + 1;
  // Lanes alternate between the two altitudes (varied depth for the camera); corners are rounded.
  std::vector<Eigen::Vector3d> pts;
  const double z[2] = {hints.ground_z_m + cfg.altitude_m[1], hints.ground_z_m + cfg.altitude_m[0]};
  for (int k = 0; k < lanes; ++k) {
    const double y = center.y() + (k - 0.5 * (lanes - 1)) * kSurveyLaneSpacing;
    const double x0 = center.x() - 0.5 * lane, x1 = center.x() + 0.5 * lane;
    pts.emplace_back(k % 2 ? x1 : x0, y, z[k % 2]);
    pts.emplace_back(k % 2 ? x0 : x1, y, z[k % 2]);
  }
  const PlanarPath path = PlanarPath::filleted_polyline(pts, kFilletRadius);
  return sample_path(path, std::min(length, path.length()), 0.0, cfg, sc.name);
}

FlightTrajectory make_waypoints(const Scenario& sc) {
  const PlanarPath path = PlanarPath::filleted_polyline(sc.trajectory.waypoints_W, kFilletRadius);
  if (path.length() < 1.0)
    throw InputError(where(sc.name, 0, "trajectory.waypoints: the points span less than 1 m horizontally"));
  return sample_path(path, path.length(), 0.0, sc.trajectory, sc.name);
}

// Along the street grid, camera forward: the route (street_route.hpp) with its corners rounded to half a street.
FlightTrajectory make_streets(const Scenario& sc, const SceneHints& hints) {
  const double length = cruise_length(sc.trajectory);
  const auto corners = detail::plan_street_route(hints, sc.trajectory, length, sc.seed, sc.name);
  const PlanarPath path = PlanarPath::filleted_polyline(corners, detail::kStreetFillet_m);
  return sample_path(path, std::min(length, path.length()), 0.0, sc.trajectory, sc.name);
}

}  // namespace

LoopsGeometry loops_geometry(const Scenario& sc, const SceneHints& hints) {
  const TrajectoryConfig& cfg = sc.trajectory;
  const double length = cruise_length(cfg);
  LoopsGeometry g;
  g.center_W = hints.tall_building_center_W;
  // Radius for `loops` loops at the cruise length, 6-30 m outside the building's half-diagonal (its corners) and
  // 3 m inside the clear zone around it when the world says how large that is.
  double hi = hints.tall_building_radius_m + 30.0;
  if (hints.clear_radius_m > 0) hi = std::min(hi, hints.clear_radius_m - 3.0);
  if (hi < hints.tall_building_radius_m + 3.0) {  // a real city's neighbours can stand that close (real_city.hpp)
    std::ostringstream m;
    m << "trajectory.altitude_m: no room to loop around the tallest building: something else stands "
      << hints.clear_radius_m << " m from its centre at the flight's height (its own corners are "
      << hints.tall_building_radius_m << " m out, a ring needs 3 m on either side); fly above it";
    throw InputError(where(sc.name, 0, m.str()));
  }
  const double lo = std::min(hints.tall_building_radius_m + 6.0, hi);
  g.radius_m = std::clamp(length / (2 * M_PI * cfg.loops), lo, hi);
  g.turns = length / (2 * M_PI * g.radius_m);
  const double range = cfg.altitude_m[1] - cfg.altitude_m[0];
  g.rise_m = std::min(cfg.loop_rise_m * g.turns, range);
  g.z_start_m = hints.ground_z_m + cfg.altitude_m[0] + 0.5 * (range - g.rise_m);
  return g;
}

FlightTrajectory make_flight_trajectory(const Scenario& scenario, const SceneHints& hints) {
  const std::string& type = scenario.trajectory.type;
  FlightTrajectory trajectory = type == "loops"     ? make_loops(scenario, hints)
                                : type == "survey"  ? make_survey(scenario, hints)
                                : type == "streets" ? make_streets(scenario, hints)
                                                    : make_waypoints(scenario);
  check_flight_limits(measure_flight(trajectory), flight_limits(scenario.trajectory), scenario.name);
  return trajectory;
}

}  // namespace twinslam::sim
