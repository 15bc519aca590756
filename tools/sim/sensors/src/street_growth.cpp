// Growing a streets route block by block to its length (street_plan.hpp).
#include <cstdlib>

#include "street_plan.hpp"

namespace twinslam::sim::detail {

namespace {

enum class Part { kStart, kMiddle, kEnd };  // start -> stretch, stretch -> park, park -> end

struct Move {
  enum Kind { kDetour, kPrepend, kAppend } kind;
  std::size_t stop;  // kDetour: around the segment stops[stop] -> stops[stop + 1]; else the end stop
  GridNode step;     // kDetour: the side of the detour; else the direction of the new segment
};

// The segments of a part: stops[k] -> stops[k + 1] for k in [first, last).
std::pair<std::size_t, std::size_t> segments_of(const RoutePlan& p, Part part) {
  const std::size_t facade = p.index_of(p.facade_start), open = p.index_of(p.open_start);
  if (part == Part::kStart) return {0, facade};
  if (part == Part::kMiddle) return {facade, open};
  return {open, p.stops.size() - 1};
}

std::vector<Move> moves_in(const RoutePlan& p, const StreetGraph& g, Part part) {
  auto free_node = [&](const GridNode& n) { return g.contains(n) && !p.used[g.index(n)]; };
  std::vector<Move> moves;
  const auto [first, last] = segments_of(p, part);
  for (std::size_t k = first; k < last; ++k) {
    if (p.stops[k].fixed_next) continue;
    const GridNode d = p.stops[k + 1].node - p.stops[k].node;
    if (std::abs(d.i) + std::abs(d.j) != 1) continue;
    for (const int sign : {1, -1}) {
      const GridNode side = d.i != 0 ? GridNode{0, sign} : GridNode{sign, 0};
      if (free_node(p.stops[k].node + side) && free_node(p.stops[k + 1].node + side))
        moves.push_back({Move::kDetour, k, side});
    }
  }
  if (part == Part::kMiddle) return moves;
  const std::size_t end = part == Part::kStart ? 0 : p.stops.size() - 1;
  for (const GridNode& step : kSteps)
    if (free_node(p.stops[end].node + step))
      moves.push_back({part == Part::kStart ? Move::kPrepend : Move::kAppend, end, step});
  return moves;
}

void apply(RoutePlan* p, const StreetGraph& g, const Move& m) {
  const GridNode at = p->stops[m.stop].node + m.step;
  switch (m.kind) {
    case Move::kDetour: {
      const GridNode next = p->stops[m.stop + 1].node + m.step;
      p->stops.insert(p->stops.begin() + static_cast<std::ptrdiff_t>(m.stop) + 1, {RouteStop(at), RouteStop(next)});
      p->used[g.index(next)] = true;
      break;
    }
    case Move::kPrepend: p->stops.insert(p->stops.begin(), RouteStop(at)); break;
    case Move::kAppend: p->stops.emplace_back(at); break;
  }
  p->used[g.index(at)] = true;
}

}  // namespace

bool grow_once(RoutePlan* plan, const StreetGraph& g, double length_m, std::mt19937_64* rng) {
  const double s_facade = plan->arc_to(g, plan->index_of(plan->facade_start));
  const double s_open = plan->arc_to(g, plan->index_of(plan->open_start));
  std::vector<Part> order{Part::kEnd, Part::kMiddle, Part::kStart};
  if (s_facade < kFacadeAt * length_m) order = {Part::kStart, Part::kMiddle, Part::kEnd};
  else if (s_open < kOpenAt * length_m) order = {Part::kMiddle, Part::kEnd, Part::kStart};
  for (const Part part : order) {
    const std::vector<Move> moves = moves_in(*plan, g, part);
    if (moves.empty()) continue;
    apply(plan, g, moves[(*rng)() % moves.size()]);
    return true;
  }
  return false;
}

}  // namespace twinslam::sim::detail
