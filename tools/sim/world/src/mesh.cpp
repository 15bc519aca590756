#include "twinslam/sim/world/mesh.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace twinslam::sim {

void TriMesh::add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           SurfaceKind k, int building) {
  const int i = static_cast<int>(p_W.size());
  p_W.push_back(a);
  p_W.push_back(b);
  p_W.push_back(c);
  triangles.emplace_back(i, i + 1, i + 2);
  building_id.push_back(building);
  kind.push_back(k);
}

void TriMesh::add_quad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d, SurfaceKind k, int building) {
  // Four shared vertices for the two triangles of one planar quad (they move together in the twin).
  const int i = static_cast<int>(p_W.size());
  p_W.insert(p_W.end(), {a, b, c, d});
  triangles.emplace_back(i, i + 1, i + 2);
  triangles.emplace_back(i, i + 2, i + 3);
  building_id.insert(building_id.end(), 2, building);
  kind.insert(kind.end(), 2, k);
}

void TriMesh::append(const TriMesh& other) {
  const int offset = static_cast<int>(p_W.size());
  p_W.insert(p_W.end(), other.p_W.begin(), other.p_W.end());
  for (const auto& t : other.triangles) triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  building_id.insert(building_id.end(), other.building_id.begin(), other.building_id.end());
  kind.insert(kind.end(), other.kind.begin(), other.kind.end());
}

Eigen::Vector3d TriMesh::normal(std::size_t tri) const {
  const auto& t = triangles[tri];
  return (p_W[t[1]] - p_W[t[0]]).cross(p_W[t[2]] - p_W[t[0]]).normalized();
}

double TriMesh::area(std::size_t tri) const {
  const auto& t = triangles[tri];
  return 0.5 * (p_W[t[1]] - p_W[t[0]]).cross(p_W[t[2]] - p_W[t[0]]).norm();
}

void TriMesh::bounds(Eigen::Vector3d* min_W, Eigen::Vector3d* max_W) const {
  if (p_W.empty()) {
    min_W->setZero();
    max_W->setZero();
    return;
  }
  *min_W = p_W.front();
  *max_W = p_W.front();
  for (const auto& p : p_W) {
    *min_W = min_W->cwiseMin(p);
    *max_W = max_W->cwiseMax(p);
  }
}

void add_box(TriMesh* mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, SurfaceKind side_kind,
             SurfaceKind top_kind, int building, bool with_bottom) {
  const std::vector<Eigen::Vector2d> outline{{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}};
  add_prism(mesh, outline, {Eigen::Vector4d(lo.x(), lo.y(), hi.x(), hi.y())}, lo.z(), hi.z(), side_kind, top_kind,
            building);
  if (with_bottom) {
    mesh->add_quad({lo.x(), lo.y(), lo.z()}, {lo.x(), hi.y(), lo.z()}, {hi.x(), hi.y(), lo.z()},
                   {hi.x(), lo.y(), lo.z()}, side_kind, building);
  }
}

void add_prism(TriMesh* mesh, const std::vector<Eigen::Vector2d>& outline, const std::vector<Eigen::Vector4d>& cap_rects,
               double z0, double z1, SurfaceKind wall_kind, SurfaceKind top_kind, int building) {
  const std::size_t n = outline.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[(i + 1) % n];
    // Counter-clockwise outline seen from above -> outward normal for a, b, b_top, a_top.
    mesh->add_quad({a.x(), a.y(), z0}, {b.x(), b.y(), z0}, {b.x(), b.y(), z1}, {a.x(), a.y(), z1}, wall_kind,
                   building);
  }
  for (const auto& r : cap_rects) {
    mesh->add_quad({r[0], r[1], z1}, {r[2], r[1], z1}, {r[2], r[3], z1}, {r[0], r[3], z1}, top_kind, building);
  }
}

void add_cone(TriMesh* mesh, const Eigen::Vector2d& c, double r, double z0, double z1, int sides, SurfaceKind kind) {
  const Eigen::Vector3d apex(c.x(), c.y(), z1);
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2.0 * M_PI * i / sides;
    const double a1 = 2.0 * M_PI * (i + 1) / sides;
    const Eigen::Vector3d p0(c.x() + r * std::cos(a0), c.y() + r * std::sin(a0), z0);
    const Eigen::Vector3d p1(c.x() + r * std::cos(a1), c.y() + r * std::sin(a1), z0);
    mesh->add_triangle(p0, p1, apex, kind, kNoBuilding);
    mesh->add_triangle(p1, p0, Eigen::Vector3d(c.x(), c.y(), z0), kind, kNoBuilding);  // underside
  }
}

}  // namespace twinslam::sim
