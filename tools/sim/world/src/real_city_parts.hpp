#pragma once
// Pieces of the real-city world shared by real_city_load.cpp (file -> labelled mesh), real_city.cpp (labelled mesh ->
// City), real_city_details.cpp (what a twin lacks) and real_city_hints.cpp (SceneHints, empty lots).
#include <string>
#include <vector>

#include "twinslam/sim/world/real_city.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::sim::detail {

// What a part of the source model is in the simulated world.
enum class PartRole {
  kBuilding,   // a building (or a part of one): facades and roofs with a building id, details added
  kStructure,  // bridges, walls, furniture: facades and roofs of no building, in every twin
  kTerrain,    // roads, land use, plant cover, water, relief: ground
};

struct SourcePart {
  PartRole role = PartRole::kBuilding;
  std::string building;  // kBuilding: the building it belongs to (parts of one building share it)
};

// The source file's geometry in W with a part per triangle.
struct SourceModel {
  twin::Mesh mesh;                     // [m, W]
  std::vector<int> part_of_triangle;   // index into parts, one per triangle
  std::vector<SourcePart> parts;
  std::vector<std::string> rejected;   // parts the loader could not use, "<file>: <reason>"
  std::vector<std::string> warnings;   // quirks accepted as CesiumJS does, one per quirk and file
};

// Reads scenario.city with the twin loaders into the W of `origin`. Throws InputError "SCENARIO: city.path: ..."
// (missing / malformed file, wrong kind for city.source).
SourceModel load_source_model(const Scenario& scenario, const Origin& origin, const RealCityConfig& config);

// Buildings, kinds and ground plane of the model (no details, no hints); `extent_W` receives the model's horizontal
// extent [min e, min n, max e, max n] before the ground margin.
City convert_source_model(const SourceModel& model, const RealCityConfig& config, Eigen::Vector4d* extent_W);

// Floor bands, balconies and rooftop boxes on the loaded buildings (kDetail, tagged with the building id).
void add_real_details(const RealCityConfig& config, std::uint64_t seed, City* city);

// city->hints and city->empty_lots_W from the built world (see real_city.hpp).
void fill_real_hints(const RealCityConfig& config, const TrajectoryConfig& trajectory, const Eigen::Vector4d& extent_W,
                     City* city);

// Horizontal distance [m] from p to triangle (a, b, c) projected on the ground plane (0 when p is inside it).
double horizontal_distance(const Eigen::Vector2d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c);

}  // namespace twinslam::sim::detail
