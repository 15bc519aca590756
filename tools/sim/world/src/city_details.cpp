// The details of the world that a digital twin does not model (issue 3, item 1). All are kDetail triangles.
#include <algorithm>
#include <cmath>

#include "city_parts.hpp"

namespace twinslam::sim::detail {

void add_quad_out(TriMesh* mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d, const Eigen::Vector3d& out, SurfaceKind kind, int building) {
  if ((b - a).cross(c - a).dot(out) >= 0) mesh->add_quad(a, b, c, d, kind, building);
  else mesh->add_quad(a, d, c, b, kind, building);
}

namespace {

// Outward unit normal of the footprint edge a->b of a counter-clockwise outline.
Eigen::Vector2d outward(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d t = (b - a).normalized();
  return {t.y(), -t.x()};
}

// Box sticking out of the wall along edge a->b: from s0 to s1 metres along the edge, depth metres out, z0..z1.
void add_wall_box(TriMesh* mesh, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double s0, double s1,
                  double depth, double z0, double z1, int building) {
  const Eigen::Vector2d t = (b - a).normalized();
  const Eigen::Vector2d n = outward(a, b);
  const Eigen::Vector2d p0 = a + s0 * t, p1 = a + s1 * t;
  const Eigen::Vector2d lo = p0.cwiseMin(p1).cwiseMin(p0 + depth * n).cwiseMin(p1 + depth * n);
  const Eigen::Vector2d hi = p0.cwiseMax(p1).cwiseMax(p0 + depth * n).cwiseMax(p1 + depth * n);
  add_box(mesh, {lo.x(), lo.y(), z0}, {hi.x(), hi.y(), z1}, SurfaceKind::kDetail, SurfaceKind::kDetail, building,
          true);
}

}  // namespace

void add_floor_bands(TriMesh* mesh, const Building& b, double floor_height_m) {
  // A 0.3 m band protruding 0.15 m at every floor line: the window rows between them sit 0.15 m back (the "window
  // recess" of a real facade), giving depth edges the flat twin facade lacks.
  const std::size_t n = b.outline_W.size();
  for (double z = floor_height_m; z < b.height_m - 0.5; z += floor_height_m) {
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& a = b.outline_W[i];
      const Eigen::Vector2d& c = b.outline_W[(i + 1) % n];
      add_wall_box(mesh, a, c, -0.15, (c - a).norm() + 0.15, 0.15, z - 0.15, z + 0.15, b.id);
    }
  }
}

void add_balconies(TriMesh* mesh, const Building& b, double floor_height_m, Rng* rng) {
  const std::size_t n = b.outline_W.size();
  const std::size_t edge = static_cast<std::size_t>(rng->integer(static_cast<int>(n)));
  for (std::size_t k = 0; k < 2; ++k) {  // this facade and the opposite-ish one
    const std::size_t i = (edge + k * (n / 2)) % n;
    const Eigen::Vector2d& a = b.outline_W[i];
    const Eigen::Vector2d& c = b.outline_W[(i + 1) % n];
    const double len = (c - a).norm();
    for (double z = floor_height_m; z < b.height_m - 1.0; z += floor_height_m) {
      for (double s = 1.5; s + 2.4 < len - 1.0; s += 6.0) {
        add_wall_box(mesh, a, c, s, s + 2.4, 1.2, z + 0.1, z + 0.3, b.id);          // slab
        const Eigen::Vector2d nrm = outward(a, c);
        const Eigen::Vector2d a2 = a + 1.15 * nrm, c2 = c + 1.15 * nrm;
        add_wall_box(mesh, a2, c2, s, s + 2.4, 0.05, z + 0.3, z + 1.3, b.id);       // railing panel
      }
    }
  }
}

void add_rooftop_boxes(TriMesh* mesh, const Eigen::Vector4d& r, double roof_z_m, int building, Rng* rng) {
  const int count = 1 + rng->integer(4);
  for (int i = 0; i < count; ++i) {
    const double w = rng->uniform(1.0, 3.0), d = rng->uniform(1.0, 3.0), h = rng->uniform(0.8, 2.5);
    if (r[2] - r[0] < w + 2 || r[3] - r[1] < d + 2) return;
    const double x = rng->uniform(r[0] + 1, r[2] - 1 - w), y = rng->uniform(r[1] + 1, r[3] - 1 - d);
    add_box(mesh, {x, y, roof_z_m}, {x + w, y + d, roof_z_m + h}, SurfaceKind::kDetail, SurfaceKind::kDetail,
            building);
  }
}

void add_tree(TriMesh* mesh, const Eigen::Vector2d& c, Rng* rng) {
  const double trunk = rng->uniform(2.0, 3.0);
  add_box(mesh, {c.x() - 0.15, c.y() - 0.15, 0.0}, {c.x() + 0.15, c.y() + 0.15, trunk}, SurfaceKind::kDetail,
          SurfaceKind::kDetail, kNoBuilding);
  add_cone(mesh, c, rng->uniform(1.4, 2.6), trunk, trunk + rng->uniform(4.0, 7.0), 8, SurfaceKind::kDetail);
}

void add_car(TriMesh* mesh, const Eigen::Vector2d& c, bool along_east, Rng* rng) {
  const double len = rng->uniform(3.8, 4.8), wid = rng->uniform(1.7, 1.9);
  const Eigen::Vector2d half = along_east ? Eigen::Vector2d(len / 2, wid / 2) : Eigen::Vector2d(wid / 2, len / 2);
  add_box(mesh, {c.x() - half.x(), c.y() - half.y(), 0.25}, {c.x() + half.x(), c.y() + half.y(), 1.0},
          SurfaceKind::kDetail, SurfaceKind::kDetail, kNoBuilding, true);
  const Eigen::Vector2d cab = half.cwiseProduct(along_east ? Eigen::Vector2d(0.5, 0.9) : Eigen::Vector2d(0.9, 0.5));
  add_box(mesh, {c.x() - cab.x(), c.y() - cab.y(), 1.0}, {c.x() + cab.x(), c.y() + cab.y(), 1.5},
          SurfaceKind::kDetail, SurfaceKind::kDetail, kNoBuilding);
}

}  // namespace twinslam::sim::detail
