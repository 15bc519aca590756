// Area-uniform point sampling of a tile's triangles with their normals (tiling.hpp).
#include <cmath>
#include <random>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/tiling.hpp"

namespace twinslam::twin {
namespace {

// SplitMix64 finalizer: spreads (seed, stream) over the generator's seed space so neighbouring tiles, whose streams
// differ by one, do not get correlated sequences.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Uniform in [0, 1) from the top 53 bits: the same numbers with every standard library (std::uniform_real_distribution
// is implementation-defined).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

Mesh sample_points(const Mesh& mesh_W, double spacing_m, std::uint64_t seed, std::uint64_t stream) {
  if (!(spacing_m > 0.0) || !std::isfinite(spacing_m)) {
    throw UsageError("point spacing must be a positive number of metres, got " + std::to_string(spacing_m));
  }
  std::mt19937_64 rng(mix(seed ^ mix(stream)));
  const double per_m2 = 1.0 / (spacing_m * spacing_m);  // expected points per square metre
  Mesh points;
  for (std::size_t t = 0; t < mesh_W.triangles.size(); ++t) {
    const double area = mesh_W.triangle_area(t);  // [m^2]
    if (!(area > 0.0)) continue;                  // degenerate: no normal, no area
    const double expected = area * per_m2;
    const double whole = std::floor(expected);
    // Draw the Bernoulli for every triangle (even when the remainder is 0) so the stream advances the same way.
    const std::size_t count = static_cast<std::size_t>(whole) + (uniform01(rng) < expected - whole ? 1 : 0);
    const Eigen::Vector3i& f = mesh_W.triangles[t];
    const Eigen::Vector3d a = mesh_W.p_W[f[0]], ab = mesh_W.p_W[f[1]] - a, ac = mesh_W.p_W[f[2]] - a;
    const Eigen::Vector3d n = mesh_W.triangle_normal(t);
    for (std::size_t k = 0; k < count; ++k) {
      double u = uniform01(rng), v = uniform01(rng);
      if (u + v > 1.0) {  // fold the far half of the parallelogram back into the triangle: uniform by area
        u = 1.0 - u;
        v = 1.0 - v;
      }
      points.p_W.push_back(a + u * ab + v * ac);
      points.n_W.push_back(n);
    }
  }
  return points;
}

}  // namespace twinslam::twin
