// The tiles service's other pure parts: the position source per vehicle (GNSS until odometry is aligned to W), the
// LRU of encoded tiles, and the config's YAML form and validation.
#include <gtest/gtest.h>

#include <map>

#include "tile_index_fixture.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/tiles/tile_cache.hpp"
#include "twinslam/tiles/tile_streamer.hpp"
#include "twinslam/tiles/tiles_config.hpp"
#include "twinslam/tiles/vehicle_positions.hpp"

namespace twinslam::tiles {
namespace {

using twin::TileKey;

TEST(VehiclePositions, GnssBeforeOdometryIsAligned) {
  VehiclePositions positions;
  TileStreamer streamer(test::grid_index(-10, 9), 150.0);
  // Only GNSS at first: the window follows it.
  const auto g = positions.on_gnss("uav0", {25, 25, 400});
  ASSERT_TRUE(g);
  EXPECT_EQ(streamer.update("uav0", *g).new_for_vehicle.size(), 9u);
  // Odometry still in the local frame L (tracking, not aligned): its T_WB is not in W and must not move the window,
  // and GNSS keeps driving it.
  EXPECT_FALSE(positions.on_odometry("uav0", false, {300, 300, 0}));
  EXPECT_TRUE(positions.on_gnss("uav0", {30, 25, 400}));
  // Aligned odometry takes over; GNSS is ignored from then on.
  const auto o = positions.on_odometry("uav0", true, {125, 25, 20});
  ASSERT_TRUE(o);
  EXPECT_EQ(streamer.update("uav0", *o).new_for_vehicle.size(), 6u);  // columns 2 and 3 (window [50, 200))
  EXPECT_FALSE(positions.on_gnss("uav0", {-400, -400, 400}));
  EXPECT_FALSE(positions.on_odometry("uav0", true, {std::nan(""), 0, 0}));
  // A reinitialization (odometry no longer aligned) hands the window back to GNSS; other vehicles are independent.
  EXPECT_FALSE(positions.on_odometry("uav0", false, {0, 0, 0}));
  EXPECT_TRUE(positions.on_gnss("uav0", {125, 25, 400}));
  EXPECT_TRUE(positions.on_gnss("uav1", {0, 0, 400}));
  EXPECT_FALSE(positions.aligned("uav1"));
}

TEST(TileCache, KeepsTheMostRecentlyUsedTilesWithinCapacity) {
  std::map<TileKey, int> loads;
  TileCache cache(2, [&](const TileRecord& info) {
    const TileKey& k = info.key;
    ++loads[k];
    if (k.ix < 0) throw InputError("tiles/" + std::to_string(k.ix) + "_0.mesh.drc: missing");
    EncodedTile t;
    t.mesh_draco.assign(100 + k.ix, 1);
    t.points_draco.assign(10, 2);
    return t;
  });
  auto get = [&](int ix) {
    TileRecord info;
    info.key = {ix, 0};
    return cache.get(info);
  };
  EXPECT_EQ(get(1)->bytes(), 111u);
  get(2);
  get(1);  // hit; (2, 0) is now the least recently used
  get(3);  // evicts (2, 0)
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.bytes(), 111u + 113u);
  get(1);
  get(2);  // loaded again
  EXPECT_EQ(loads[(TileKey{1, 0})], 1);
  EXPECT_EQ(loads[(TileKey{2, 0})], 2);
  EXPECT_EQ(cache.hits(), 2u);
  EXPECT_EQ(cache.misses(), 4u);
  // A failing load passes its error on and caches nothing.
  EXPECT_THROW(get(-1), InputError);
  EXPECT_EQ(cache.size(), 2u);
}

TEST(TilesConfig, YamlAndValidation) {
  const TilesConfig c = parse_tiles_config("window_m: 200\ncache_tiles: 16\ntwin_dir: /data/twin\n", "t.yaml");
  EXPECT_EQ(c.window_m, 200.0);
  EXPECT_EQ(c.cache_tiles, 16);
  EXPECT_EQ(c.twin_dir, "/data/twin");
  TilesConfig base;
  base.twin_dir = "/x";
  EXPECT_EQ(parse_tiles_config("", "t.yaml", base).window_m, 250.0);  // defaults kept
  auto message = [&](const std::string& text) {
    try {
      parse_tiles_config(text, "t.yaml", base).validate("t.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("window_m: -1\n"), "t.yaml: tiles key 'window_m': must lie in (0, 1000] m, got -1.000000");
  EXPECT_EQ(message("max_tiles_on_wire: 0\n"), "t.yaml: tiles key 'max_tiles_on_wire': must be >= 1, got 0");
  EXPECT_EQ(message("cache_tiles: 0\n"), "t.yaml: tiles key 'cache_tiles': must be >= 1, got 0");
  EXPECT_EQ(message("window: 3\n"),
            "t.yaml:1: tiles key 'window': unknown key (known: window_m, cache_tiles, twin_dir, max_tiles_on_wire)");
  EXPECT_EQ(message("cache_tiles: many\n"), "t.yaml:1: tiles key 'cache_tiles': expected an integer");
  EXPECT_NE(message("[1, 2"), "no error");
  EXPECT_THROW(parse_tiles_config("window_m: 100\n", "t.yaml").validate("t.yaml"), InputError);  // no twin_dir
}

}  // namespace
}  // namespace twinslam::tiles
