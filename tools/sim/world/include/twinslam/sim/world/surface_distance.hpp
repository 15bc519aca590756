#pragma once
// How far one surface is from another: points sampled uniformly by area on `sampled` (the twin) and, for each, the
// distance to the nearest point of `reference` (the world) by an Embree closest-point query.
// Not symmetric: world details the twin lacks do not count, twin-only (added) buildings do.
#include <cstdint>
#include <vector>

#include "twinslam/sim/world/mesh.hpp"

namespace twinslam::sim {

struct SurfaceSample {
  Eigen::Vector3d p_W;        // [m, W]
  std::uint32_t triangle = 0; // index into TriMesh::triangles
};

// Points uniformly distributed over the mesh's area (triangle by area, then a uniform point in it), seeded.
// Also a source of landmarks for ideal feature tracks. Throws InputError if the mesh has no area or samples < 1.
std::vector<SurfaceSample> sample_surface(const TriMesh& mesh, int samples, std::uint64_t seed);

struct SurfaceDistance {
  int samples = 0;
  double rms_m = 0;      // root mean square distance [m]
  double median_m = 0;
  double p95_m = 0;
  double max_m = 0;      // capped at the search radius
};

// Throws InputError if `sampled` has no area or samples < 1. Distances beyond max_search_m count as max_search_m.
SurfaceDistance surface_distance(const TriMesh& sampled, const TriMesh& reference, int samples, std::uint64_t seed,
                                 double max_search_m = 50.0);

}  // namespace twinslam::sim
