#pragma once
// The street grid of SceneHints as a graph: nodes are the intersections of the street centrelines, edges the street
// segments between neighbouring intersections (one block long). Private to the library (streets flights).
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim::detail {

struct GridNode {
  int i = 0;  // index into StreetGrid::east_m (which north-south street)
  int j = 0;  // index into StreetGrid::north_m (which east-west street)
  friend bool operator==(const GridNode& a, const GridNode& b) { return a.i == b.i && a.j == b.j; }
  friend bool operator!=(const GridNode& a, const GridNode& b) { return !(a == b); }
  GridNode operator+(const GridNode& d) const { return {i + d.i, j + d.j}; }
  GridNode operator-(const GridNode& d) const { return {i - d.i, j - d.j}; }
};

// The four unit steps along the streets: east, north, west, south.
inline constexpr GridNode kSteps[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};

class StreetGraph {
 public:
  explicit StreetGraph(const StreetGrid& grid) : grid_(grid) {}

  int nx() const { return static_cast<int>(grid_.east_m.size()); }
  int ny() const { return static_cast<int>(grid_.north_m.size()); }
  int size() const { return nx() * ny(); }
  bool contains(const GridNode& n) const { return n.i >= 0 && n.j >= 0 && n.i < nx() && n.j < ny(); }
  int index(const GridNode& n) const { return n.i * ny() + n.j; }
  Eigen::Vector2d position(const GridNode& n) const { return {grid_.east_m[n.i], grid_.north_m[n.j]}; }  // [m, W]
  double street_width_m() const { return grid_.width_m; }

  // Fewest-segment path from a to b (both included) through nodes whose `blocked` flag (by index()) is false; a and
  // b may be blocked. Empty if there is none. Ties go to the first of kSteps, so the result is deterministic.
  std::vector<GridNode> shortest_path(const GridNode& a, const GridNode& b, const std::vector<bool>& blocked) const;

 private:
  StreetGrid grid_;
};

}  // namespace twinslam::sim::detail
