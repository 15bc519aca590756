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

double Mesh::total_area() const {
  double sum = 0.0;
  for (std::size_t i = 0; i < triangles.size(); ++i) sum += triangle_area(i);
  return sum;
}

}  // namespace twinslam::twin
