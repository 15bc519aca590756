#pragma once
// The route of a streets flight while it is planned: stops at intersections (some fixed together as the facade
// stretch and the open-square crossing), built as a skeleton with both features and grown block by block to length.
// Private to the library.
#include <cstddef>
#include <optional>
#include <random>
#include <vector>

#include "facade_stretch.hpp"
#include "street_graph.hpp"

namespace twinslam::sim::detail {

struct RouteStop {
  GridNode node;
  Eigen::Vector2d shift_W = Eigen::Vector2d::Zero();  // off the intersection's centre (facade stretch ends) [m]
  bool fixed_next = false;  // the segment to the next stop belongs to a feature: growth must not touch it
  bool low = false;         // flown at the lowest altitude (the facade stretch)

  explicit RouteStop(const GridNode& n, bool fixed = false) : node(n), fixed_next(fixed) {}
  RouteStop(const GridNode& n, const Eigen::Vector2d& shift, bool fixed, bool is_low)
      : node(n), shift_W(shift), fixed_next(fixed), low(is_low) {}
};

struct RoutePlan {
  std::vector<RouteStop> stops;
  std::vector<bool> used;        // by StreetGraph::index(): intersections the route passes (never twice)
  GridNode facade_start;         // first stop of the facade stretch
  GridNode open_start;           // first stop of the open-square crossing (the diagonal follows)

  std::size_t index_of(const GridNode& n) const;
  Eigen::Vector2d position(const StreetGraph& g, std::size_t k) const {  // of stop k [m, W]
    return g.position(stops[k].node) + stops[k].shift_W;
  }
  // Length of the route [m] up to stop k along the straight segments (corners not rounded).
  double arc_to(const StreetGraph& g, std::size_t k) const;
  // Horizontal length of the flown path: corners rounded with kStreetFillet_m [m].
  double filleted_length(const StreetGraph& g) const;
};

// A park block between four intersections: corners sw, sw + (1, 0), sw + (0, 1), sw + (1, 1).
struct ParkBlock {
  GridNode sw;
  Eigen::Vector2d centre_W = Eigen::Vector2d::Zero();
};
std::vector<ParkBlock> park_blocks(const StreetGraph& g, const std::vector<Eigen::Vector4d>& open_areas_W);

// Start (two segments) -> the facade stretch (entered and left by a turn, so its shifted line needs no jog) -> the
// shortest connection -> the diagonal across a park (entered and left by 45 deg turns) -> a straight tail. The park
// farthest from the stretch that can be connected is taken. nullopt if no combination fits the grid.
std::optional<RoutePlan> build_skeleton(const StreetGraph& g, const FacadeStretch& facade,
                                        const std::vector<ParkBlock>& parks);

// Lengthens the plan by one block (a detour around the block beside an unfixed segment, or one more segment at the
// start or the end) in the part of the route that is behind its share (start -> stretch: kFacadeAt of length_m,
// stretch -> park: kOpenAt), chosen at random among the possibilities. false if nothing can grow anywhere.
inline constexpr double kFacadeAt = 0.12;  // the stretch starts after this fraction of the flight
inline constexpr double kOpenAt = 0.55;    // the park crossing starts after this fraction
bool grow_once(RoutePlan* plan, const StreetGraph& g, double length_m, std::mt19937_64* rng);

}  // namespace twinslam::sim::detail
