#pragma once
// Pieces of the procedural city shared by city.cpp (layout, building shells) and city_details.cpp (what a twin lacks).
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/random.hpp"

namespace twinslam::sim::detail {

// Quad whose winding is fixed so its normal points along `out` (callers need not think about vertex order).
void add_quad_out(TriMesh* mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d, const Eigen::Vector3d& out, SurfaceKind kind, int building);

// Details of one building (kind kDetail, tagged with the building id so a missing building loses them too).
void add_floor_bands(TriMesh* mesh, const Building& b, double floor_height_m);
void add_balconies(TriMesh* mesh, const Building& b, double floor_height_m, Rng* rng);
void add_rooftop_boxes(TriMesh* mesh, const Eigen::Vector4d& roof_rect_W, double roof_z_m, int building, Rng* rng);

// Street furniture (kNoBuilding).
void add_tree(TriMesh* mesh, const Eigen::Vector2d& c_W, Rng* rng);
void add_car(TriMesh* mesh, const Eigen::Vector2d& c_W, bool along_east, Rng* rng);

}  // namespace twinslam::sim::detail
