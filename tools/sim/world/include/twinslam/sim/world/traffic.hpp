#pragma once
// Moving cars on the procedural city's streets (issue 13, item 6, `traffic:` scenario keys): in the camera images and
// in the ideal feature tracks, never in the world mesh, so never in the twin derived from it nor in the GNSS ray
// tracing.
//
// Streets: the centrelines of SceneHints::streets between their intersections. Every street is one-way with a single
// lane on its centreline (the city's parked cars stand 1.5-3.3 m either side of it): the outermost streets of the grid
// circulate clockwise around it and the inner ones alternate direction, like a Manhattan grid, so every intersection
// has a way on. Street pieces whose middle is within SceneHints::clear_radius_m of the tower (when that is unknown, as
// in the procedural city: the tower's half-diagonal plus a street width) are closed: the ring the loops flight circles
// over stays free, as it is of parked cars and trees. A car starts at a seeded place on a
// seeded street piece, drives at speed_mps without stopping, and at each intersection goes straight on or takes the
// turn the one-way streets allow (seeded, even odds), through a quarter circle of half a street's width. Cars do not
// see one another: at a crossing two may overlap for a moment.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/sim/scenario.hpp"
#include "twinslam/sim/world/mesh.hpp"

namespace twinslam::sim {

class TrafficSnapshot;

class Traffic {
 public:
  // Routes for simulation times [-1, duration_s + 1] s (a frame's readout and exposure reach a little beyond the
  // flight; outside, a car stands at its route's end). No street grid (empty hints.streets) or config.cars == 0: no
  // cars. Throws InputError for a negative or non-finite cars / speed_mps.
  Traffic(const SceneHints& hints, const TrafficSimConfig& config, double duration_s, std::uint64_t seed);
  ~Traffic();
  Traffic(const Traffic&) = delete;
  Traffic& operator=(const Traffic&) = delete;

  std::size_t size() const { return cars_.size(); }
  bool empty() const { return cars_.empty(); }

  // Car k's frame V (x forward, y left, z up; origin on the ground under the middle of the car) in W at time t_s.
  Eigen::Isometry3d T_WV(std::size_t k, double t_s) const;
  // Car k's body in V: body, cabin and wheels as boxes (kind kDetail; building_id = the part, CarPart).
  const TriMesh& mesh_V(std::size_t k) const { return cars_[k].mesh_V; }
  float paint(std::size_t k) const { return cars_[k].paint; }  // albedo of its paint
  double speed_mps(std::size_t k) const { return cars_[k].speed_mps; }
  // A sphere that holds car k throughout [t0_s, t1_s]: centre [m, W], radius [m].
  std::pair<Eigen::Vector3d, double> bounding_sphere(std::size_t k, double t0_s, double t1_s) const;

  // The cars during [t0_s, t1_s] as an Embree scene (each car's vertices move linearly from its pose at t0 to that at
  // t1: over a frame's few milliseconds this is exact to well under a millimetre); only the cars listed in `only`
  // (indices) if given. The snapshot must not outlive this.
  std::unique_ptr<TrafficSnapshot> snapshot(double t0_s, double t1_s,
                                            const std::vector<std::size_t>* only = nullptr) const;

 private:
  // One part of a route: a straight line or a circular arc (a turn).
  struct Piece {
    double s_m = 0;                       // arc length of the route at its start [m]
    double length_m = 0;
    Eigen::Vector2d a_W = Eigen::Vector2d::Zero();  // line: its start; arc: the circle's centre [m, E N]
    double angle_rad = 0;                 // line: heading; arc: direction from the centre to the start
    double turn = 0;                      // 0 line, +1 left (counter-clockwise), -1 right
    double radius_m = 0;                  // arc only
  };
  struct Car {
    std::vector<Piece> route;
    double s0_m = 0;                      // arc length at t = 0
    double speed_mps = 0;
    TriMesh mesh_V;
    Eigen::Vector3d centre_V = Eigen::Vector3d::Zero();  // of its bounding box
    double radius_m = 0;                                   // half the box's diagonal
    float paint = 0.3f;
  };
  struct Impl;
  std::vector<Car> cars_;
  std::unique_ptr<Impl> impl_;  // the Embree device the snapshots are built on
  friend class TrafficSnapshot;
};

enum CarPart : int { kCarBody = 0, kCarCabin = 1, kCarWheel = 2 };

struct CarHit {
  std::size_t car = 0;
  double t_m = 0;                         // distance along the unit ray [m]
  Eigen::Vector3d p_V, n_V;               // hit point and outward normal in the car's frame
  int part = kCarBody;
};

class TrafficSnapshot {
 public:
  ~TrafficSnapshot();
  TrafficSnapshot(const TrafficSnapshot&) = delete;
  TrafficSnapshot& operator=(const TrafficSnapshot&) = delete;

  const Traffic& traffic() const { return traffic_; }
  double t0_s() const { return t0_s_; }
  double t1_s() const { return t1_s_; }
  const std::vector<std::size_t>& cars() const { return cars_; }  // the cars it holds
  // Embree's ray time in [0, 1] for simulation time t_s (clamped to the window).
  float ray_time(double t_s) const;
  // RTCScene: one geometry (id 0) of all its cars' triangles; nullptr when it holds none.
  void* rtc_scene() const { return scene_; }

  // First car surface on origin_W + t dir_W (dir_W unit), 0 < t < t_max, at time t_s.
  bool intersect(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double t_s, double t_max,
                 CarHit* hit) const;
  bool occluded(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double t_s, double t_max) const;
  // A hit's car, point and normal in the car's frame, from Embree's primitive id and barycentric coordinates (u, v).
  void local_hit(std::uint32_t primitive, float u, float v, CarHit* hit) const;

 private:
  friend class Traffic;
  TrafficSnapshot(const Traffic& traffic, double t0_s, double t1_s, std::vector<std::size_t> cars);
  const Traffic& traffic_;
  double t0_s_, t1_s_;
  std::vector<std::size_t> cars_;
  std::vector<std::uint32_t> first_;  // first primitive of each of cars_, then the total
  void* scene_ = nullptr;
};

}  // namespace twinslam::sim
