#include "twinslam/sim/flight_surroundings.hpp"

#include <algorithm>
#include <cmath>

namespace twinslam::sim {

namespace {

// Horizontal distance from p to the axis-aligned rectangle r [min e, min n, max e, max n] [m].
double distance_to_rect(const Eigen::Vector2d& p, const Eigen::Vector4d& r) {
  const double dx = std::max({r[0] - p.x(), 0.0, p.x() - r[2]});
  const double dy = std::max({r[1] - p.y(), 0.0, p.y() - r[3]});
  return std::hypot(dx, dy);
}

}  // namespace

std::vector<int> buildings_along_flight(const FlightTrajectory& trajectory, const std::vector<BuildingHint>& buildings,
                                        double within_m) {
  std::vector<Eigen::Vector2d> path;
  for (double t = 0; t <= trajectory.duration(); t += 0.5) path.push_back(trajectory.at(t).p_W.head<2>());
  std::vector<int> ids;
  for (const BuildingHint& b : buildings) {
    const bool near = std::any_of(path.begin(), path.end(), [&](const Eigen::Vector2d& p) {
      return std::any_of(b.rects_W.begin(), b.rects_W.end(),
                         [&](const Eigen::Vector4d& r) { return distance_to_rect(p, r) <= within_m; });
    });
    if (near) ids.push_back(b.id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<int> twin_change_candidates(const Scenario& scenario, const SceneHints& hints,
                                        const FlightTrajectory& trajectory) {
  if (scenario.trajectory.type != "streets") return {};
  return buildings_along_flight(trajectory, hints.buildings, kSeenWithin_m);
}

}  // namespace twinslam::sim
