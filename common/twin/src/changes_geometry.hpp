#pragma once
// Geometry behind twin-change detection (changes.hpp): a horizontal grid over a mesh's triangles for nearby-surface
// and segment queries, segment-triangle crossings, the convex hull of a point set (the closest point on a triangle
// is mesh.hpp's).
#include <optional>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin::detail {

// Triangles binned by their horizontal bounding box into square cells.
class TriangleGrid {
 public:
  TriangleGrid(const Mesh& mesh, double cell_m);
  // Indices of the triangles whose cells overlap the horizontal box [lo, hi] (each at most once).
  std::vector<int> near(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const;

 private:
  long long key(long ix, long iy) const { return (static_cast<long long>(ix) << 32) ^ static_cast<unsigned>(iy); }
  double cell_m_;
  std::size_t triangles_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

// Where the segment from -> to crosses triangle (a, b, c), as the fraction t in (0, 1) of the way (Moller-Trumbore).
std::optional<double> segment_crosses(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& a,
                                      const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain); fewer than 3 points as given.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points);

}  // namespace twinslam::twin::detail
