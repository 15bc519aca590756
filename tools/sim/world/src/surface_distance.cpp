#include "twinslam/sim/world/surface_distance.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/embree_scene.hpp"
#include "twinslam/sim/world/random.hpp"

namespace twinslam::sim {

SurfaceDistance surface_distance(const TriMesh& sampled, const TriMesh& reference, int samples, std::uint64_t seed,
                                 double max_search_m) {
  if (samples < 1) throw InputError("surface_distance: need at least one sample");
  std::vector<double> cumulative(sampled.num_triangles());
  double total = 0;
  for (std::size_t i = 0; i < sampled.num_triangles(); ++i) cumulative[i] = total += sampled.area(i);
  if (!(total > 0)) throw InputError("surface_distance: the sampled mesh has no area");

  const EmbreeScene scene(reference);
  Rng rng(seed);
  std::vector<double> d(samples);
  double sum_sq = 0;
  for (int s = 0; s < samples; ++s) {
    // Triangle with probability proportional to its area, then a uniform point in it (sqrt warp of barycentrics).
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), rng.uniform() * total);
    const std::size_t tri = std::min<std::size_t>(it - cumulative.begin(), cumulative.size() - 1);
    const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
    const auto& t = sampled.triangles[tri];
    const Eigen::Vector3d p = (1 - r1) * sampled.p_W[t[0]] + r1 * (1 - r2) * sampled.p_W[t[1]] +
                              r1 * r2 * sampled.p_W[t[2]];
    d[s] = std::min(scene.closest_distance(p, max_search_m), max_search_m);
    sum_sq += d[s] * d[s];
  }
  SurfaceDistance out;
  out.samples = samples;
  out.rms_m = std::sqrt(sum_sq / samples);
  std::sort(d.begin(), d.end());
  out.median_m = d[samples / 2];
  out.p95_m = d[std::min(samples - 1, static_cast<int>(0.95 * samples))];
  out.max_m = d.back();
  return out;
}

}  // namespace twinslam::sim
