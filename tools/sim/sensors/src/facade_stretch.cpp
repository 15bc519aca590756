#include "facade_stretch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace twinslam::sim::detail {

namespace {

// Along/lateral extent of an axis-aligned rectangle in the frame (origin a, axes u, side) [m].
struct Extent {
  double along_lo, along_hi, lateral_lo;
};

Extent extent_of(const Eigen::Vector4d& r, const Eigen::Vector2d& a, const Eigen::Vector2d& u,
                 const Eigen::Vector2d& side) {
  Extent e{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()};
  const Eigen::Vector2d corners[4] = {{r[0], r[1]}, {r[2], r[1]}, {r[2], r[3]}, {r[0], r[3]}};
  for (const Eigen::Vector2d& c : corners) {
    e.along_lo = std::min(e.along_lo, (c - a).dot(u));
    e.along_hi = std::max(e.along_hi, (c - a).dot(u));
    e.lateral_lo = std::min(e.lateral_lo, (c - a).dot(side));
  }
  return e;
}

}  // namespace

double facade_coverage(const Eigen::Vector2d& a_W, const Eigen::Vector2d& b_W, const Eigen::Vector2d& side_W,
                       const std::vector<BuildingHint>& buildings, double min_eave_m, double min_top_m,
                       double street_width_m, double* nearest_m) {
  const double length = (b_W - a_W).norm();
  const Eigen::Vector2d u = (b_W - a_W) / length;
  std::vector<Extent> tall, any;
  for (const BuildingHint& b : buildings)
    for (const Eigen::Vector4d& r : b.rects_W) {
      const Extent e = extent_of(r, a_W, u, side_W);
      if (e.lateral_lo <= 0 || e.along_hi < 0 || e.along_lo > length) continue;  // other side or beyond the ends
      if (b.height_m >= min_eave_m) tall.push_back(e);
      if (b.top_m >= min_top_m) any.push_back(e);
    }
  *nearest_m = std::numeric_limits<double>::infinity();
  for (const Extent& e : any) *nearest_m = std::min(*nearest_m, e.lateral_lo);
  // Sampled every metre between the intersections (half a street width from each end node).
  int covered = 0, samples = 0;
  for (double s = 0.5 * street_width_m; s <= length - 0.5 * street_width_m; s += 1.0, ++samples) {
    for (const Extent& e : tall)
      if (s >= e.along_lo && s <= e.along_hi && e.lateral_lo <= kFacadeReach_m) {
        ++covered;
        break;
      }
  }
  return samples > 0 ? static_cast<double>(covered) / samples : 0.0;
}

std::vector<FacadeStretch> rank_facade_stretches(const StreetGraph& graph, const std::vector<BuildingHint>& buildings,
                                                 double z_m) {
  std::vector<FacadeStretch> ranked;
  for (const GridNode& step : {kSteps[0], kSteps[1]}) {  // east-west streets, then north-south streets
    const Eigen::Vector2d u(step.i, step.j), left(-u.y(), u.x());
    for (int i = 0; i < graph.nx(); ++i)
      for (int j = 0; j < graph.ny(); ++j) {
        const GridNode a{i, j}, b{i + kFacadeBlocks * step.i, j + kFacadeBlocks * step.j};
        if (!graph.contains(b)) continue;
        for (const Eigen::Vector2d& side : {left, Eigen::Vector2d(-left)}) {
          const Eigen::Vector2d pa = graph.position(a), pb = graph.position(b);
          const double w = graph.street_width_m();
          double nearest = 0, nearest_other = 0;
          FacadeStretch f;
          f.coverage = facade_coverage(pa, pb, side, buildings, z_m + kFacadeRise_m, z_m - kRoofClearance_m, w,
                                       &nearest);
          f.opposite_coverage = facade_coverage(pa, pb, -side, buildings, 0.0, 0.0, w, &nearest_other);
          for (int k = 0; k <= kFacadeBlocks; ++k) f.nodes.push_back({i + k * step.i, j + k * step.j});
          f.side_W = side;
          // Closer to the row, but never nearer than kFacadeDistance_m to any footprint on that side.
          f.shift_m = std::clamp(nearest - kFacadeDistance_m, 0.0, 0.5 * w - 1.0);
          ranked.push_back(f);
        }
      }
  }
  // Most lined side first; an emptier opposite side only breaks ties (weighing it more picks rows with gaps: a
  // degenerate view needs the wall more than the emptiness across); then grid order.
  std::stable_sort(ranked.begin(), ranked.end(), [](const FacadeStretch& x, const FacadeStretch& y) {
    return x.coverage != y.coverage ? x.coverage > y.coverage : x.opposite_coverage < y.opposite_coverage;
  });
  return ranked;
}

}  // namespace twinslam::sim::detail
