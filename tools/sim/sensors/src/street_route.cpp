// plan_street_route: checks, the two features, growth to length and the altitude profile (street_plan.hpp).
#include "street_route.hpp"

#include <cmath>
#include <sstream>

#include "seeds.hpp"
#include "street_plan.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::sim::detail {

namespace {

constexpr double kAltitudeWavelength_m = 600;  // one climb and descent through altitude_m per 600 m of route

[[noreturn]] void fail(const std::string& what, const std::string& key, const std::string& message) {
  throw InputError(where(what, 0, key + ": " + message));
}

// Corners at the stops: the facade stretch at the lowest altitude, elsewhere a slow wave through altitude_m that
// starts from its lowest point at the stretch (so the climb out of the canyon is gentle).
std::vector<Eigen::Vector3d> corners_of(const RoutePlan& plan, const StreetGraph& g, const TrajectoryConfig& config,
                                        double ground_z_m) {
  const double lo = ground_z_m + config.altitude_m[0], hi = ground_z_m + config.altitude_m[1];
  const double s_facade = plan.arc_to(g, plan.index_of(plan.facade_start));
  std::vector<Eigen::Vector3d> corners;
  double s = 0;
  for (std::size_t k = 0; k < plan.stops.size(); ++k) {
    if (k > 0) s += (plan.position(g, k) - plan.position(g, k - 1)).norm();
    const double wave = 0.5 * (1 - std::cos(2 * M_PI * (s - s_facade) / kAltitudeWavelength_m));  // 0..1
    const double z = plan.stops[k].low ? lo : lo + (hi - lo) * wave;
    const Eigen::Vector2d p = plan.position(g, k);
    corners.emplace_back(p.x(), p.y(), z);
  }
  return corners;
}

std::string grid_text(const StreetGraph& g) {
  return std::to_string(g.nx()) + " x " + std::to_string(g.ny()) + " intersections";
}

}  // namespace

std::vector<Eigen::Vector3d> plan_street_route(const SceneHints& hints, const TrajectoryConfig& config,
                                               double length_m, std::uint64_t seed, const std::string& what) {
  const StreetGraph g(hints.streets);
  if (g.nx() < 2 || g.ny() < 2)
    fail(what, "trajectory.type", "streets needs a street grid between blocks (a procedural city of >= 3 x 3 blocks)");
  const double min_altitude = hints.furniture_top_m + kFurnitureClearance_m;
  if (config.altitude_m[0] < min_altitude) {
    std::ostringstream m;
    m << "a streets flight must stay >= " << min_altitude << " m above ground (street trees reach "
      << hints.furniture_top_m << " m); min is " << config.altitude_m[0];
    fail(what, "trajectory.altitude_m", m.str());
  }
  const auto stretches = rank_facade_stretches(g, hints.buildings, hints.ground_z_m + config.altitude_m[0]);
  if (stretches.empty())
    fail(what, "city.size_m", "the street grid (" + grid_text(g) + ") has no straight run of " +
                                  std::to_string(kFacadeBlocks) + " blocks for the facade stretch");
  const std::vector<ParkBlock> parks = park_blocks(g, hints.open_areas_W);
  if (parks.empty())
    fail(what, "city.size_m",
         "no park between streets to cross as the open square (try another seed or a larger city)");
  std::optional<RoutePlan> plan;
  for (std::size_t k = 0; k < stretches.size() && !plan; ++k) plan = build_skeleton(g, stretches[k], parks);
  if (!plan) fail(what, "city.size_m", "the street grid (" + grid_text(g) + ") cannot connect a stretch and a park");

  std::mt19937_64 rng = make_rng(seed, Stream::Route);
  // A skeleton already longer than the flight (a short --duration) is flown as far as it goes, features or not.
  const bool grown = plan->filleted_length(g) < length_m;
  while (plan->filleted_length(g) < length_m)
    if (!grow_once(&*plan, g, length_m, &rng)) {
      std::ostringstream m;
      m << "the street grid (" << grid_text(g) << ") holds no " << length_m
        << " m route that flies every street once; enlarge the city or shorten the flight (trajectory.duration_s, "
           "trajectory.speed_mps)";
      fail(what, "city.size_m", m.str());
    }
  // The flight ends after length_m: the park crossing must lie before that.
  const std::size_t open = plan->index_of(plan->open_start);
  if (grown && plan->arc_to(g, open + 1) > length_m)
    fail(what, "city.size_m", "the route grew past its length before reaching the park (" + grid_text(g) + ")");
  return corners_of(*plan, g, config, hints.ground_z_m);
}

}  // namespace twinslam::sim::detail
