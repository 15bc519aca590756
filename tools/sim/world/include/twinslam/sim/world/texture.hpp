#pragma once
// 3D-consistent procedural texture: the albedo is a function of the surface point p_W, its normal, kind and
// building only, never of the camera, so a surface point looks the same from every frame and corners track.
// Patterns have hard-edged cells (windows, slabs, tiles) because Shi-Tomasi/KLT need corners, not smooth noise.
#include "twinslam/sim/world/mesh.hpp"

namespace twinslam::sim {

// Albedo in [0, 0.72] (kept below the sky so silhouettes stay bright-to-dark edges).
// footprint_m: size of one pixel on the surface [m]; patterns finer than about 2-4 px fade to their mean, a cheap
// stand-in for mip-mapping that stops distant facades from flickering between frames.
float albedo(const Eigen::Vector3d& p_W, const Eigen::Vector3d& n_W, SurfaceKind kind, int building,
             double footprint_m);

// Albedo of a moving car (traffic.hpp) from its point and normal in the car's own frame V, so the pattern moves with
// the car: `paint`, glass all round the cabin between its pillars, dark sills and bumpers, light clusters front and
// back, black tyres. part: CarPart (0 body, 1 cabin, 2 wheel).
float car_albedo(const Eigen::Vector3d& p_V, const Eigen::Vector3d& n_V, int part, float paint, double footprint_m);

}  // namespace twinslam::sim
