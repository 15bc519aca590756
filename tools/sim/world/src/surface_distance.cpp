#include "twinslam/sim/world/surface_distance.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/embree_scene.hpp"
#include "twinslam/sim/world/random.hpp"

namespace twinslam::sim {

std::vector<SurfaceSample> sample_surface(const TriMesh& mesh, int samples, std::uint64_t seed) {
  if (samples < 1) throw InputError("sample_surface: need at least one sample");
  std::vector<double> cumulative(mesh.num_triangles());
  double total = 0;
  for (std::size_t i = 0; i < mesh.num_triangles(); ++i) cumulative[i] = total += mesh.area(i);
  if (!(total > 0)) throw InputError("sample_surface: the mesh has no area");
  Rng rng(seed);
  std::vector<SurfaceSample> out(samples);
  for (auto& s : out) {
    // Triangle with probability proportional to its area, then a uniform point in it (sqrt warp of barycentrics).
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), rng.uniform() * total);
    s.triangle = static_cast<std::uint32_t>(std::min<std::size_t>(it - cumulative.begin(), cumulative.size() - 1));
    const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
    const auto& t = mesh.triangles[s.triangle];
    s.p_W = (1 - r1) * mesh.p_W[t[0]] + r1 * (1 - r2) * mesh.p_W[t[1]] + r1 * r2 * mesh.p_W[t[2]];
  }
  return out;
}

SurfaceDistance surface_distance(const TriMesh& sampled, const TriMesh& reference, int samples, std::uint64_t seed,
                                 double max_search_m) {
  const std::vector<SurfaceSample> points = sample_surface(sampled, samples, seed);
  const EmbreeScene scene(reference);
  std::vector<double> d(samples);
  double sum_sq = 0;
  for (int s = 0; s < samples; ++s) {
    d[s] = std::min(scene.closest_distance(points[s].p_W, max_search_m), max_search_m);
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
