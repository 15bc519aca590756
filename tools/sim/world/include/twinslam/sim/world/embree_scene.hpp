#pragma once
// A TriMesh in an Embree 3 BVH: ray casting for the renderer and visibility tests, closest-point queries for the
// world-to-twin surface distance. Thread-safe for queries after construction (Embree's scenes are read-only then).
#include <cstdint>
#include <memory>

#include <Eigen/Core>

#include "twinslam/sim/world/mesh.hpp"

namespace twinslam::sim {

struct RayHit {
  double t_m = 0;              // distance along the (unit) direction [m]
  std::uint32_t triangle = 0;  // index into TriMesh::triangles
  Eigen::Vector3d n_W;         // unit geometric normal, facing the ray origin
};

class EmbreeScene {
 public:
  explicit EmbreeScene(const TriMesh& mesh);  // copies the mesh; throws std::runtime_error if Embree fails
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  const TriMesh& mesh() const { return mesh_; }

  // First hit of the ray origin_W + t dir_W (dir_W unit) with t in (t_min, t_max); false if nothing is hit.
  bool intersect(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double t_min, double t_max,
                 RayHit* hit) const;

  // Distance [m] from p_W to the nearest surface point, searched up to max_m; +infinity if nothing is that close.
  // triangle (optional) receives the index of the nearest triangle when one is found.
  double closest_distance(const Eigen::Vector3d& p_W, double max_m, std::uint32_t* triangle = nullptr) const;

  void* rtc_scene() const;  // RTCScene, for packet tracing in the renderer

 private:
  struct Impl;
  TriMesh mesh_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace twinslam::sim
