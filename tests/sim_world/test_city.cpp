// Procedural city: deterministic per seed, one clearly tallest building at the centre, twin-less details present.
#include <algorithm>
#include <cmath>
#include <map>
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

TEST(SimWorldCity, HintsDescribeTheStreetsParksAndFootprints) {
  CityConfig config;
  config.size_m = 300;  // 5 x 5 blocks: 4 streets between them on each axis
  const City city = build_city(config, 7);
  const StreetGrid& g = city.hints.streets;
  ASSERT_EQ(g.east_m.size(), 4u);
  EXPECT_EQ(g.north_m, g.east_m);
  EXPECT_DOUBLE_EQ(g.width_m, city.layout.street_width_m);
  // No footprint reaches into a street, and every gap between two blocks has a centreline in its middle.
  for (const Building& b : city.buildings)
    for (const Eigen::Vector4d& r : b.rects_W)
      for (const double x : g.east_m) {
        EXPECT_TRUE(r[2] <= x - 0.5 * g.width_m || r[0] >= x + 0.5 * g.width_m) << "building " << b.id;
        EXPECT_TRUE(r[3] <= x - 0.5 * g.width_m || r[1] >= x + 0.5 * g.width_m) << "building " << b.id;
      }
  for (std::size_t k = 1; k < g.east_m.size(); ++k)
    EXPECT_DOUBLE_EQ(g.east_m[k] - g.east_m[k - 1], city.layout.block_size_m + city.layout.street_width_m);
  // Footprints as the world has them; parks are empty lots with no building on them.
  ASSERT_EQ(city.hints.buildings.size(), city.buildings.size());
  for (const Building& b : city.buildings) {
    EXPECT_EQ(city.hints.buildings[b.id].rects_W, b.rects_W);
    EXPECT_EQ(city.hints.buildings[b.id].top_m, b.top_m);
  }
  const City big = build_city(CityConfig{}, 7);
  EXPECT_GT(big.hints.open_areas_W.size(), 0u);
  for (const Eigen::Vector4d& park : big.hints.open_areas_W) {
    EXPECT_NE(std::find(big.empty_lots_W.begin(), big.empty_lots_W.end(), park), big.empty_lots_W.end());
    EXPECT_DOUBLE_EQ(park[2] - park[0], big.layout.block_size_m);  // whole blocks
  }
  EXPECT_GT(big.hints.furniture_top_m, 5.0);   // trees: 2-3 m trunk + 4-7 m crown
  EXPECT_LE(big.hints.furniture_top_m, 10.0);
}

// The 3D-aliased city (issue 15, item 4): every block but the tower's holds the same buildings at the same place
// within it, so a street looks the same one block pitch further on; the default city's blocks differ.
std::map<std::pair<int, int>, std::vector<std::vector<double>>> buildings_per_block(const City& city) {
  const double pitch = city.layout.block_size_m + city.layout.street_width_m;
  std::map<std::pair<int, int>, std::vector<std::vector<double>>> out;
  for (const Building& b : city.buildings) {
    if (b.id == city.tallest_id) continue;
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : b.outline_W) c += p / static_cast<double>(b.outline_W.size());
    const int i = static_cast<int>(std::lround(c.x() / pitch)), j = static_cast<int>(std::lround(c.y() / pitch));
    std::vector<double> shape{b.height_m, b.top_m};  // the outline relative to its block's centre, to the mm
    for (const auto& p : b.outline_W)
      for (const double v : {p.x() - i * pitch, p.y() - j * pitch}) shape.push_back(std::round(v * 1000) / 1000);
    out[{i, j}].push_back(shape);
  }
  for (auto& [block, shapes] : out) std::sort(shapes.begin(), shapes.end());
  return out;
}

TEST(SimWorldCity, IdenticalBlocksRepeatOneBlockOverTheWholeGrid) {
  CityConfig config;
  config.size_m = 400;
  config.blocks = "identical";
  const auto blocks = buildings_per_block(build_city(config, 7));
  ASSERT_EQ(blocks.size(), 24u);  // 5 x 5 blocks, the tower's aside: no parks
  for (const auto& [block, shapes] : blocks) EXPECT_EQ(shapes, blocks.begin()->second);
  EXPECT_EQ(build_city(config, 7).mesh.p_W, build_city(config, 7).mesh.p_W);

  config.blocks = "varied";
  const auto varied = buildings_per_block(build_city(config, 7));
  int same = 0;
  for (const auto& [block, shapes] : varied) same += shapes == varied.begin()->second;
  EXPECT_LT(same, 3);
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
  config = CityConfig{};
  config.blocks = "repeated";
  EXPECT_THROW(build_city(config, 1), InputError);
}

}  // namespace
}  // namespace twinslam::sim
