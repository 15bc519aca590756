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

// The flight's horizontal positions every 0.5 s [m, W].
std::vector<Eigen::Vector2d> sampled_path(const FlightTrajectory& trajectory) {
  std::vector<Eigen::Vector2d> path;
  for (double t = 0; t <= trajectory.duration(); t += 0.5) path.push_back(trajectory.at(t).p_W.head<2>());
  return path;
}

bool near_path(const std::vector<Eigen::Vector2d>& path, const Eigen::Vector4d& r, double within_m) {
  return std::any_of(path.begin(), path.end(),
                     [&](const Eigen::Vector2d& p) { return distance_to_rect(p, r) <= within_m; });
}

}  // namespace

std::vector<int> buildings_along_flight(const FlightTrajectory& trajectory, const std::vector<BuildingHint>& buildings,
                                        double within_m) {
  const std::vector<Eigen::Vector2d> path = sampled_path(trajectory);
  std::vector<int> ids;
  for (const BuildingHint& b : buildings) {
    if (std::any_of(b.rects_W.begin(), b.rects_W.end(),
                    [&](const Eigen::Vector4d& r) { return near_path(path, r, within_m); }))
      ids.push_back(b.id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<int> lots_along_flight(const FlightTrajectory& trajectory, const std::vector<Eigen::Vector4d>& lots_W,
                                   double within_m) {
  const std::vector<Eigen::Vector2d> path = sampled_path(trajectory);
  std::vector<int> out;
  for (std::size_t k = 0; k < lots_W.size(); ++k)
    if (near_path(path, lots_W[k], within_m)) out.push_back(static_cast<int>(k));
  return out;
}

}  // namespace twinslam::sim
