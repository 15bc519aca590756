#pragma once
// Test geometry for the twin store: a small city of boxes on a ground grid, built in code so tests need no loader.
#include <cstdint>
#include <random>

#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin::test {

// Axis-aligned closed box as 12 triangles, counter-clockwise seen from outside.
inline void add_box(Mesh* m, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const int base = static_cast<int>(m->p_W.size());
  for (int i = 0; i < 8; ++i) {
    m->p_W.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m->triangles.emplace_back(base + q[0], base + q[1], base + q[2]);
    m->triangles.emplace_back(base + q[0], base + q[2], base + q[3]);
  }
}

// Ground of `cells` x `cells` squares of `cell` metres from (e0, n0), gently sloped so heights vary, plus boxes of
// random size and height that straddle tile lines at random; deterministic per seed.
inline Mesh box_city(double e0, double n0, int cells, double cell, int boxes, std::uint64_t seed) {
  Mesh m;
  const auto z = [](double e, double n) { return 0.01 * e - 0.02 * n; };
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const double e = e0 + i * cell, n = n0 + j * cell;
      m.p_W.emplace_back(e, n, z(e, n));
    }
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int a = j * (cells + 1) + i, b = a + 1, c = a + cells + 2, d = a + cells + 1;
      m.triangles.emplace_back(a, b, c);
      m.triangles.emplace_back(a, c, d);
    }
  }
  std::mt19937_64 rng(seed);
  const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  const double span = cells * cell;
  for (int k = 0; k < boxes; ++k) {
    const Eigen::Vector3d lo(e0 + u() * span * 0.9, n0 + u() * span * 0.9, 0.0);
    const Eigen::Vector3d size(5 + 30 * u(), 5 + 30 * u(), 4 + 60 * u());
    add_box(&m, lo, (lo + size).cwiseMin(Eigen::Vector3d(e0 + span, n0 + span, 1e9)));
  }
  return m;
}

}  // namespace twinslam::twin::test
