#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

void Mesh::append(const Mesh& other) {
  const int offset = static_cast<int>(p_W.size());
  const bool keep_normals = n_W.size() == p_W.size() && other.n_W.size() == other.p_W.size();
  if (keep_normals) {
    n_W.insert(n_W.end(), other.n_W.begin(), other.n_W.end());
  } else {
    n_W.clear();
  }
  p_W.insert(p_W.end(), other.p_W.begin(), other.p_W.end());
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const Eigen::Vector3i& t : other.triangles) triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

void Mesh::transform(const Eigen::Isometry3d& T) {
  for (Eigen::Vector3d& p : p_W) p = T * p;
  for (Eigen::Vector3d& n : n_W) n = T.linear() * n;
}

Eigen::AlignedBox3d Mesh::bounds() const {
  Eigen::AlignedBox3d box;  // empty
  for (const Eigen::Vector3d& p : p_W) box.extend(p);
  return box;
}

Eigen::Vector3d Mesh::triangle_normal(std::size_t tri) const {
  const Eigen::Vector3i& t = triangles[tri];
  const Eigen::Vector3d n = (p_W[t[1]] - p_W[t[0]]).cross(p_W[t[2]] - p_W[t[0]]);
  const double norm = n.norm();
  return norm > 0.0 ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
}

double Mesh::triangle_area(std::size_t tri) const {
  const Eigen::Vector3i& t = triangles[tri];
  return 0.5 * (p_W[t[1]] - p_W[t[0]]).cross(p_W[t[2]] - p_W[t[0]]).norm();
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  // Voronoi regions of the vertices, then the edges, then the face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double Mesh::total_area() const {
  double sum = 0.0;
  for (std::size_t i = 0; i < triangles.size(); ++i) sum += triangle_area(i);
  return sum;
}

}  // namespace twinslam::twin
