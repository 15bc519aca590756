// The skeleton of a streets route: start, facade stretch, connection, park diagonal, tail (street_plan.hpp).
#include <algorithm>

#include "street_plan.hpp"

namespace twinslam::sim::detail {

namespace {

GridNode perpendicular(const GridNode& step, int sign) { return step.i != 0 ? GridNode{0, sign} : GridNode{sign, 0}; }

// The diagonal p0 -> p1 across a park, entered from `entry` and left along `tail_step`: both straight segments meet
// the diagonal at 45 deg, so the corners stay inside the intersections.
struct Crossing {
  GridNode p0, p1, entry, tail_step;
};

std::vector<Crossing> crossings_of(const ParkBlock& park) {
  std::vector<Crossing> out;
  for (const int sx : {1, -1})
    for (const int sy : {1, -1}) {
      const GridNode p0{park.sw.i + (sx > 0 ? 0 : 1), park.sw.j + (sy > 0 ? 0 : 1)};
      const GridNode p1{p0.i + sx, p0.j + sy};
      for (const GridNode& in : {GridNode{sx, 0}, GridNode{0, sy}})
        for (const GridNode& out_step : {GridNode{sx, 0}, GridNode{0, sy}}) out.push_back({p0, p1, p0 - in, out_step});
    }
  return out;
}

constexpr int kTailSegments = 3;  // straight segments after the park: what the flight's end may cut stays off it

// Start and stretch fixed by the caller (`head`, whose nodes are marked in `used`, ending at the stretch's exit
// r0); connects them to `c` if the grid allows.
std::optional<RoutePlan> connect(const StreetGraph& g, RoutePlan head, const GridNode& r0, const Crossing& c) {
  std::vector<GridNode> tail{c.p0, c.p1};
  for (int k = 1; k <= kTailSegments; ++k) tail.push_back(c.p1 + GridNode{k * c.tail_step.i, k * c.tail_step.j});
  std::vector<bool> blocked = head.used;
  for (const GridNode& n : tail) {
    if (!g.contains(n) || blocked[g.index(n)] || n == r0) return std::nullopt;
    blocked[g.index(n)] = true;
  }
  if (!g.contains(c.entry) || (blocked[g.index(c.entry)] && c.entry != r0)) return std::nullopt;
  const std::vector<GridNode> path = g.shortest_path(r0, c.entry, blocked);
  if (path.empty()) return std::nullopt;
  for (const GridNode& n : path) head.stops.emplace_back(n);
  head.stops.back().fixed_next = true;  // entry -> p0
  for (std::size_t k = 0; k < tail.size(); ++k) head.stops.emplace_back(tail[k], k < 2);  // p0 -> p1 -> t1 fixed
  for (const GridNode& n : path) head.used[g.index(n)] = true;
  for (const GridNode& n : tail) head.used[g.index(n)] = true;
  head.open_start = c.p0;
  return head;
}

// Two straight segments into the stretch's first node from the `start_sign` side, the stretch with both ends moved
// toward its facades, and the exit node r0 on the `exit_sign` side. nullopt if it leaves the grid.
std::optional<std::pair<RoutePlan, GridNode>> head_of(const StreetGraph& g, const FacadeStretch& f,
                                                      const std::vector<GridNode>& a, int start_sign, int exit_sign) {
  const GridNode travel = a[1] - a[0];
  const GridNode q0 = a.front() + perpendicular(travel, start_sign), s = q0 + perpendicular(travel, start_sign);
  const GridNode r0 = a.back() + perpendicular(travel, exit_sign);
  if (!g.contains(s) || !g.contains(r0)) return std::nullopt;
  RoutePlan plan;
  plan.used.assign(static_cast<std::size_t>(g.size()), false);
  for (const GridNode& n : {s, q0}) plan.used[g.index(n)] = true;
  for (const GridNode& n : a) plan.used[g.index(n)] = true;
  if (plan.used[g.index(r0)]) return std::nullopt;
  const Eigen::Vector2d shift = f.shift_m * f.side_W;
  plan.stops = {RouteStop(s), RouteStop(q0, true), RouteStop(a.front(), shift, true, true),
                RouteStop(a.back(), shift, true, true)};
  plan.facade_start = a.front();
  return std::make_pair(plan, r0);
}

}  // namespace

std::optional<RoutePlan> build_skeleton(const StreetGraph& g, const FacadeStretch& facade,
                                        const std::vector<ParkBlock>& parks) {
  const Eigen::Vector2d mid = 0.5 * (g.position(facade.nodes.front()) + g.position(facade.nodes.back()));
  std::vector<ParkBlock> by_distance = parks;
  std::stable_sort(by_distance.begin(), by_distance.end(), [&](const ParkBlock& x, const ParkBlock& y) {
    return (x.centre_W - mid).norm() > (y.centre_W - mid).norm();
  });
  for (const ParkBlock& park : by_distance)
    for (const bool reverse : {false, true}) {
      std::vector<GridNode> a = facade.nodes;
      if (reverse) std::reverse(a.begin(), a.end());
      for (const int start_sign : {1, -1})
        for (const int exit_sign : {1, -1}) {
          const auto head = head_of(g, facade, a, start_sign, exit_sign);
          if (!head) continue;
          for (const Crossing& c : crossings_of(park))
            if (auto plan = connect(g, head->first, head->second, c)) return plan;
        }
    }
  return std::nullopt;
}

}  // namespace twinslam::sim::detail
