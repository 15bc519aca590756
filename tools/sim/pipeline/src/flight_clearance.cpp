#include "twinslam/sim/flight_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/embree_scene.hpp"

namespace twinslam::sim {
namespace {

constexpr double kSearch_m = 50.0;  // closest-point search radius [m]

std::string fixed(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

// The world without its flat ground: what a drone can hit besides the ground it takes off from.
TriMesh obstacles(const City& city, double ground_band_m) {
  const TriMesh& w = city.mesh;
  TriMesh out;
  for (std::size_t i = 0; i < w.num_triangles(); ++i) {
    const auto& t = w.triangles[i];
    if (w.kind[i] == SurfaceKind::kGround) {
      const double top = std::max({w.p_W[t[0]].z(), w.p_W[t[1]].z(), w.p_W[t[2]].z()});
      if (top < city.hints.ground_z_m + ground_band_m) continue;
    }
    out.add_triangle(w.p_W[t[0]], w.p_W[t[1]], w.p_W[t[2]], w.kind[i], w.building_id[i]);
  }
  return out;
}

}  // namespace

FlightClearance measure_flight_clearance(const City& city, const FlightTrajectory& trajectory,
                                         const FlightClearanceConfig& config) {
  const EmbreeScene scene(obstacles(city, config.ground_band_m));
  FlightClearance c;
  c.min_distance_m = kSearch_m;
  const auto n = static_cast<long>(std::ceil(trajectory.duration() / config.sample_dt_s));
  for (long k = 0; k <= n; ++k) {
    const double t = std::min(trajectory.duration(), static_cast<double>(k) * config.sample_dt_s);
    const Eigen::Vector3d p = trajectory.at(t).p_W;
    std::uint32_t tri = 0;
    const double d = scene.closest_distance(p, c.min_distance_m, &tri);
    if (!(d < c.min_distance_m)) continue;
    c.min_distance_m = d;
    c.t_s = t;
    c.p_W = p;
    c.building = scene.mesh().building_id[tri];
  }
  return c;
}

void require_flight_clearance(const Scenario& scenario, const City& city, const FlightTrajectory& trajectory,
                              const FlightClearanceConfig& config) {
  const FlightClearance c = measure_flight_clearance(city, trajectory, config);
  if (c.min_distance_m >= config.min_distance_m) return;
  std::string what = "a structure, tree or raised ground";
  if (c.building != kNoBuilding) {
    const Building& b = city.buildings[static_cast<std::size_t>(c.building)];
    what = "building " + std::to_string(b.id) + (b.name.empty() ? "" : " '" + b.name + "'") + " (" + fixed(b.top_m) +
           " m high)";
  }
  const std::string& type = scenario.trajectory.type;
  const std::string key = type == "waypoints" ? "trajectory.waypoints" : "trajectory.altitude_m";
  throw InputError(where(scenario.name, 0,
                         key + ": the flight passes " + fixed(c.min_distance_m) + " m from " + what + " at t = " +
                             fixed(c.t_s) + " s (E " + fixed(c.p_W.x()) + ", N " + fixed(c.p_W.y()) + ", U " +
                             fixed(c.p_W.z()) + " m); it must keep " + fixed(config.min_distance_m) +
                             " m from buildings and structures"));
}

}  // namespace twinslam::sim
