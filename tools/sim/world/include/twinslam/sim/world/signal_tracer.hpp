#pragma once
// GNSS signal paths in the simulated city (issue 13, gnss.model: raytrace): for a receiver and a satellite direction,
// is the direct path free (line of sight), and if not, does a single bounce off a building facade reach the receiver
// (multipath / NLOS), with how much extra path?
//
// Mirror-image method: a plane wall with unit normal n reflects the signal as if it came to the receiver's mirror
// image p' = p - 2 h n (h = distance of p in front of the wall). The reflection point is where the line from p'
// toward the satellite crosses the wall; the bounce is real only if that point lies on the facade, nothing blocks the
// leg receiver -> wall, and nothing blocks the leg wall -> satellite.
//
// Far-satellite approximation: every ray toward the satellite is parallel (one direction s for the whole city). At
// 20 000 km the true direction changes by < 1e-5 rad over 200 m, so the path error is < 1 mm. The extra path of a
// bounce is then (p - p')·s = 2 h (s·n), independent of the range.
//
// Queries are const and touch no shared mutable state: trace() is thread-safe, as EmbreeScene's queries are.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/world/embree_scene.hpp"

namespace twinslam::sim {

struct SignalPath {
  bool line_of_sight = false;     // the direct ray to the satellite is unobstructed
  bool reflected = false;         // a single-bounce path off a facade reaches the receiver (searched when the direct
                                  // ray is blocked, or always with also_with_line_of_sight: multipath)
  double extra_path_m = 0;        // reflected path minus the direct range [m] (> 0); 0 when !reflected
  Eigen::Vector3d reflection_point_W = Eigen::Vector3d::Zero();  // where the reflected signal hits the facade [m, W]
  int building = -1;              // building_id of the reflecting facade, -1 if none
};

struct SignalTracerConfig {
  double max_reflection_distance_m = 150;  // facades farther than this from the receiver are not considered [m]
  double min_facade_area_m2 = 1.0;         // smaller triangles are ignored as reflectors [m^2]
  double grid_cell_m = 25;                 // side of the facade index's XY cells [m]
};

class SignalTracer {
 public:
  // Indexes the scene's facade triangles (SurfaceKind::kFacade, near-vertical) in a 2-D grid once; keeps a reference
  // to the scene (which must outlive the tracer).
  SignalTracer(const EmbreeScene& scene, SignalTracerConfig config = {});

  // p_W receiver [m, W = ENU]; to_satellite_W unit vector from the receiver to the satellite (W).
  // also_with_line_of_sight: look for the reflection even when the direct ray is clear (the receiver then gets both:
  // code multipath); otherwise only blocked signals are traced further (NLOS).
  SignalPath trace(const Eigen::Vector3d& p_W, const Eigen::Vector3d& to_satellite_W,
                   bool also_with_line_of_sight = false) const;

  std::size_t num_facades() const { return facades_.size(); }  // indexed reflector triangles

 private:
  struct Facade {
    Eigen::Vector3d n_W;          // outward unit normal
    Eigen::Vector3d a_W;          // first vertex: a point of the plane
    Eigen::Vector4d box_xy;       // XY bounds [min x, min y, max x, max y] [m, W]
    std::uint32_t triangle = 0;   // index into TriMesh::triangles
    int cell_x0 = 0, cell_y0 = 0;  // first grid cell the box covers (visit each facade once per query)
  };
  struct Bounce {
    double extra_path_m;
    std::uint32_t facade;
    Eigen::Vector3d point_W;
  };

  void build_grid();
  std::vector<Bounce> mirror_bounces(const Eigen::Vector3d& p_W, const Eigen::Vector3d& s_W) const;
  bool inside_triangle(std::uint32_t triangle, const Eigen::Vector3d& x_W, const Eigen::Vector3d& n_W) const;
  bool bounce_is_clear(const Eigen::Vector3d& p_W, const Eigen::Vector3d& s_W, const Bounce& bounce) const;

  const EmbreeScene& scene_;
  SignalTracerConfig config_;
  std::vector<Facade> facades_;
  Eigen::Vector2d grid_origin_xy_ = Eigen::Vector2d::Zero();  // [m, W]
  double cell_m_ = 25;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> cell_start_;  // CSR: facades of cell (ix, iy) are cell_items_[start[k], start[k + 1])
  std::vector<std::uint32_t> cell_items_;
};

}  // namespace twinslam::sim
