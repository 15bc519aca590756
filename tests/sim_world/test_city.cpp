// Procedural city: deterministic per seed, one clearly tallest building at the centre, twin-less details present.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/city.hpp"

namespace twinslam::sim {
namespace {

TEST(SimWorldCity, SameSeedSameMeshDifferentSeedDifferentMesh) {
  const City a = build_city(CityConfig{}, 7);
  const City b = build_city(CityConfig{}, 7);
  const City c = build_city(CityConfig{}, 8);
  EXPECT_EQ(a.mesh.p_W, b.mesh.p_W);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.kind, b.mesh.kind);
  EXPECT_EQ(a.mesh.building_id, b.mesh.building_id);
  EXPECT_NE(a.mesh.p_W, c.mesh.p_W);
}

TEST(SimWorldCity, TallestBuildingIsAtTheCentreAndClearlyTallest) {
  CityConfig config;  // height_m [8, 60]
  const City city = build_city(config, 7);
  const Building& tower = city.buildings.at(city.tallest_id);
  EXPECT_DOUBLE_EQ(tower.height_m, 60.0);
  for (const auto& b : city.buildings) {
    if (b.id == city.tallest_id) continue;
    EXPECT_LE(b.top_m, 0.8 * tower.height_m) << "building " << b.id;
    EXPECT_GE(b.height_m, 3.0);
  }
  EXPECT_NEAR(city.hints.tall_building_center_W.norm(), 0.0, 1e-9);
  EXPECT_NEAR(city.hints.tall_building_radius_m, 14.0 * std::sqrt(2.0), 1e-9);
  EXPECT_DOUBLE_EQ(city.hints.tall_building_height_m, 60.0);
  EXPECT_EQ(city.hints.extent_W[0], -300.0);
  EXPECT_EQ(city.hints.extent_W[3], 300.0);
  // The mesh stays inside the extent and above the ground.
  Eigen::Vector3d lo, hi;
  city.mesh.bounds(&lo, &hi);
  EXPECT_GE(lo.x(), -300.0);
  EXPECT_LE(hi.y(), 300.0);
  EXPECT_GE(lo.z(), 0.0);
}

TEST(SimWorldCity, HasEveryKindVariedFootprintsAndEmptyLots) {
  const City city = build_city(CityConfig{}, 7);
  std::set<SurfaceKind> kinds(city.mesh.kind.begin(), city.mesh.kind.end());
  EXPECT_EQ(kinds.size(), 4u);
  const auto l_shapes = std::count_if(city.buildings.begin(), city.buildings.end(),
                                      [](const Building& b) { return b.outline_W.size() == 6; });
  EXPECT_GT(l_shapes, 5);
  EXPECT_GT(city.buildings.size(), 100u);
  EXPECT_GT(city.empty_lots_W.size(), 2u);
  // Heights spread over the configured range.
  double lo = 1e9, hi = 0;
  for (const auto& b : city.buildings)
    if (b.id != city.tallest_id) lo = std::min(lo, b.height_m), hi = std::max(hi, b.height_m);
  EXPECT_LE(lo, 12.0);
  EXPECT_GE(hi, 27.0);
}

TEST(SimWorldCity, BadConfigIsInputError) {
  CityConfig config;
  config.size_m = 10;
  EXPECT_THROW(build_city(config, 1), InputError);
  config = CityConfig{};
  config.height_m = {30, 20};
  EXPECT_THROW(build_city(config, 1), InputError);
  config = CityConfig{};
  config.source = "osm";
  EXPECT_THROW(build_city(config, 1), InputError);
}

}  // namespace
}  // namespace twinslam::sim
