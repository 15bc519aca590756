#include "street_plan.hpp"

#include <cmath>

#include "path.hpp"
#include "street_route.hpp"

namespace twinslam::sim::detail {

std::size_t RoutePlan::index_of(const GridNode& n) const {
  for (std::size_t k = 0; k < stops.size(); ++k)
    if (stops[k].node == n) return k;
  return stops.size();
}

double RoutePlan::arc_to(const StreetGraph& g, std::size_t k) const {
  double s = 0;
  for (std::size_t m = 1; m <= k && m < stops.size(); ++m) s += (position(g, m) - position(g, m - 1)).norm();
  return s;
}

double RoutePlan::filleted_length(const StreetGraph& g) const {
  std::vector<Eigen::Vector3d> corners;
  for (std::size_t k = 0; k < stops.size(); ++k) {
    const Eigen::Vector2d p = position(g, k);
    corners.emplace_back(p.x(), p.y(), 0.0);
  }
  return PlanarPath::filleted_polyline(corners, kStreetFillet_m).length();
}

std::vector<ParkBlock> park_blocks(const StreetGraph& g, const std::vector<Eigen::Vector4d>& open_areas_W) {
  // A block lies between two neighbouring centrelines on each axis, half a street in from each of them.
  const double half = 0.5 * g.street_width_m(), tol = 0.5;  // [m]
  std::vector<ParkBlock> parks;
  for (const Eigen::Vector4d& r : open_areas_W) {
    for (int i = 0; i + 1 < g.nx(); ++i)
      for (int j = 0; j + 1 < g.ny(); ++j) {
        const Eigen::Vector2d lo = g.position({i, j}), hi = g.position({i + 1, j + 1});
        if (std::abs(lo.x() + half - r[0]) < tol && std::abs(lo.y() + half - r[1]) < tol &&
            std::abs(hi.x() - half - r[2]) < tol && std::abs(hi.y() - half - r[3]) < tol)
          parks.push_back({{i, j}, 0.5 * (lo + hi)});
      }
  }
  return parks;
}

}  // namespace twinslam::sim::detail
