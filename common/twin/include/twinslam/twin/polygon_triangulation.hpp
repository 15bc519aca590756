#pragma once
// Triangulation of one planar polygon with holes in 3D (CityJSON surfaces, OSM roofs and bottoms): the rings are
// projected into the polygon's best-fit plane (Newell normal of the outer ring), holes are bridged into the outer
// ring (Eberly, "Triangulation by Ear Clipping"), and the result is ear-clipped. O(n^2) per polygon: fine for the
// tens to hundreds of vertices of a building surface.
#include <vector>

#include <Eigen/Core>

namespace twinslam::twin {

// rings[0] is the outer boundary, rings[1..] are holes; each ring lists indices into `points` (not repeating the
// first vertex at the end). Returns triangles (indices into `points`) wound like the outer ring, so their normals
// agree with the outer ring's Newell normal. Degenerate input (fewer than 3 distinct vertices, zero area, bad
// indices) gives no triangles; holes with fewer than 3 vertices are ignored.
std::vector<Eigen::Vector3i> triangulate_polygon(const std::vector<Eigen::Vector3d>& points,
                                                 const std::vector<std::vector<int>>& rings);

// The Newell normal of a ring (not normalized: its length is twice the ring's vector area) [m^2].
Eigen::Vector3d newell_normal(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& ring);

}  // namespace twinslam::twin
