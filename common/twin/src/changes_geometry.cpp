#include "changes_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace twinslam::twin::detail {

TriangleGrid::TriangleGrid(const Mesh& mesh, double cell_m) : cell_m_(cell_m), triangles_(mesh.triangles.size()) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    Eigen::Vector2d lo = mesh.p_W[mesh.triangles[t][0]].head<2>(), hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.p_W[mesh.triangles[t][k]].head<2>());
      hi = hi.cwiseMax(mesh.p_W[mesh.triangles[t][k]].head<2>());
    }
    for (long ix = std::lround(std::floor(lo.x() / cell_m)); ix <= std::lround(std::floor(hi.x() / cell_m)); ++ix)
      for (long iy = std::lround(std::floor(lo.y() / cell_m)); iy <= std::lround(std::floor(hi.y() / cell_m)); ++iy)
        cells_[key(ix, iy)].push_back(static_cast<int>(t));
  }
}

std::vector<int> TriangleGrid::near(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const {
  std::vector<int> out;
  for (long ix = std::lround(std::floor(lo.x() / cell_m_)); ix <= std::lround(std::floor(hi.x() / cell_m_)); ++ix)
    for (long iy = std::lround(std::floor(lo.y() / cell_m_)); iy <= std::lround(std::floor(hi.y() / cell_m_)); ++iy)
      if (const auto it = cells_.find(key(ix, iy)); it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
  // A large triangle (the ground) is in many cells: once is enough.
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::optional<double> segment_crosses(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& a,
                                      const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = to - from, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-12) return std::nullopt;  // parallel to the triangle's plane
  const Eigen::Vector3d s = from - a;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = e2.dot(q) / det;
  if (t <= 0 || t >= 1) return std::nullopt;
  return t;
}

std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(),
            [](const auto& p, const auto& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace twinslam::twin::detail
