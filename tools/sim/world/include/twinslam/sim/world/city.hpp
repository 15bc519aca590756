#pragma once
// Procedural city (issue 3, item 1): a street grid over CityConfig::size_m, blocks of buildings with rectangular and
// L-shaped footprints, heights in CityConfig::height_m, one clearly tallest tower at the centre (the `loops`
// trajectory circles it), roof structures, a ground plane, and the details a twin does not have (floor bands that set
// the window rows back, balconies, rooftop boxes, trees, parked cars). Deterministic per seed.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/sim/scenario.hpp"
#include "twinslam/sim/world/mesh.hpp"

namespace twinslam::sim {

// Layout constants of the street grid [m].
struct CityLayout {
  double street_width_m = 12;
  double block_size_m = 48;                 // side of a square block between streets
  double floor_height_m = 3;                // storey height: window rows and floor bands follow it
  double ground_patch_m = 20;               // the ground plane is tiled so the twin can perturb it patch by patch
};

struct Building {
  int id = 0;
  std::vector<Eigen::Vector2d> outline_W;   // footprint, counter-clockwise [m, E N]
  std::vector<Eigen::Vector4d> rects_W;     // footprint as union of rectangles [min e, min n, max e, max n]
  double height_m = 0;                      // eave (main roof) height above ground [m]
  double top_m = 0;                         // highest point incl. roof structures [m]
  // Loaded cities (real_city.hpp): the height of the ground it stands on [m, W up] (0 in the procedural city) and its
  // identity in the source file (CityJSON object id, "osm way 123", "component 7"); heights above are above base_z_m.
  double base_z_m = 0;
  std::string name;
};

struct City {
  TriMesh mesh;                             // the world, details included [m, W]
  std::vector<Building> buildings;          // buildings[i].id == i == TriMesh::building_id
  int tallest_id = 0;
  std::vector<Eigen::Vector4d> empty_lots_W;  // lots without a building (parks, parking) [min e, min n, max e, max n]
  SceneHints hints;
  CityLayout layout;
};

// Throws InputError if size_m or height_m are out of range (size_m < 60, height_m not increasing or <= 2 m).
City build_city(const CityConfig& config, std::uint64_t seed, const CityLayout& layout = {});

}  // namespace twinslam::sim
