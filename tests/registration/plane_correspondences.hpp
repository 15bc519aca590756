#pragma once
// Noise-free correspondences (a = b) on ideal planes, for the information's tests.
#include <vector>

#include <Eigen/Core>

#include "twinslam/registration/icp.hpp"

namespace twinslam::registration::test {

// An 11 x 11 grid on the plane through `o` spanned by u and v (normal u x v), relative to the pivot c = (0, 0, 0).
inline void plane(std::vector<Correspondence>& out, const Eigen::Vector3d& o, const Eigen::Vector3d& u,
                  const Eigen::Vector3d& v) {
  const Eigen::Vector3d n = u.cross(v).normalized();
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const Eigen::Vector3d p = o + 0.1 * i * u + 0.1 * j * v;
      out.push_back({p, p, n, 0.0, 0.0});
    }
  }
}

}  // namespace twinslam::registration::test
