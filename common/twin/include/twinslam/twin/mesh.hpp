#pragma once
// The one geometry type every twin loader produces: a triangle mesh (or a point set with normals) in the world
// frame W (East-North-Up, metres, origin = the twin's GeoOrigin). Loaders convert their source frame (ECEF, a
// projected CRS, glTF y-up) into W before returning, so later stages never see a source frame.
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::twin {

struct Mesh {
  std::vector<Eigen::Vector3d> p_W;        // vertices [m, W]
  std::vector<Eigen::Vector3i> triangles;  // vertex indices, counter-clockwise seen from outside where the source says
  std::vector<Eigen::Vector3d> n_W;        // optional unit normals per vertex (point sets); empty or size p_W.size()

  std::size_t num_vertices() const { return p_W.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  bool empty() const { return p_W.empty(); }

  // Appends `other`, re-indexing its triangles. Normals are kept only if both (or neither) have them.
  void append(const Mesh& other);
  // Applies p' = T * p (and rotates normals) to every vertex.
  void transform(const Eigen::Isometry3d& T);
  // Axis-aligned bounds of all vertices [m, W]; an empty box for an empty mesh.
  Eigen::AlignedBox3d bounds() const;
  // Unit normal (right-handed winding) and area [m^2] of triangle `tri`; zero normal for a degenerate triangle.
  Eigen::Vector3d triangle_normal(std::size_t tri) const;
  double triangle_area(std::size_t tri) const;
  double total_area() const;
};

// Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection, 2005, sec. 5.1.5).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

}  // namespace twinslam::twin
