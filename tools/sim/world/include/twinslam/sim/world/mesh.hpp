#pragma once
// Triangle mesh of the simulated world (and of its digital twin) in W: East-North-Up, metres, z up.
// Every triangle owns its three vertices (no sharing across planar faces): flat shading needs no per-vertex normals,
// and the twin can offset each planar face along its own normal without tearing neighbours apart.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace twinslam::sim {

// What a triangle is: the renderer picks a texture by kind, the twin drops kDetail.
enum class SurfaceKind : std::uint8_t {
  kGround = 0,  // streets, pavements, parks
  kFacade = 1,  // building walls
  kRoof = 2,    // roof surfaces and roof structures that a twin models (penthouses, gables)
  kDetail = 3,  // what a twin does not model: balconies, floor bands, rooftop boxes, trees, cars
};

constexpr int kNoBuilding = -1;  // building_id of triangles that belong to no building

struct TriMesh {
  std::vector<Eigen::Vector3d> p_W;                 // vertices [m, W]
  std::vector<Eigen::Vector3i> triangles;           // vertex indices, counter-clockwise seen from outside
  std::vector<int> building_id;                     // per triangle; kNoBuilding for ground, trees, cars
  std::vector<SurfaceKind> kind;                    // per triangle

  std::size_t num_triangles() const { return triangles.size(); }
  void add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, SurfaceKind k,
                    int building);
  // Quad a-b-c-d (counter-clockwise seen from outside) as two triangles.
  void add_quad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d, SurfaceKind k, int building);
  void append(const TriMesh& other);

  Eigen::Vector3d normal(std::size_t tri) const;  // unit normal (right-handed winding) of a triangle
  double area(std::size_t tri) const;             // [m^2]
  // Axis-aligned bounds of all vertices [m, W]; zero box for an empty mesh.
  void bounds(Eigen::Vector3d* min_W, Eigen::Vector3d* max_W) const;
};

// Closed axis-aligned box [min_W, max_W]; all six faces get `kind` except a top face kind if given.
void add_box(TriMesh* mesh, const Eigen::Vector3d& min_W, const Eigen::Vector3d& max_W, SurfaceKind side_kind,
             SurfaceKind top_kind, int building, bool with_bottom = false);

// Vertical prism over a counter-clockwise polygon outline (x, y) from z0 to z1: walls plus a top cap built from
// `cap_rects` (axis-aligned rectangles [min_x, min_y, max_x, max_y] whose union is the polygon), so non-convex
// footprints such as L-shapes need no general triangulation.
void add_prism(TriMesh* mesh, const std::vector<Eigen::Vector2d>& outline, const std::vector<Eigen::Vector4d>& cap_rects,
               double z0, double z1, SurfaceKind wall_kind, SurfaceKind top_kind, int building);

// Cone (tree crown) with `sides` faces around (cx, cy), radius r [m], from z0 up to the apex at z1.
void add_cone(TriMesh* mesh, const Eigen::Vector2d& c, double r, double z0, double z1, int sides, SurfaceKind kind);

}  // namespace twinslam::sim
