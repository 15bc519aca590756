// The per-tile twin index: exact nearest neighbours across tile borders, incremental updates equal a fresh build,
// loading from the store and from MapTile bytes, clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "synthetic_twin.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/registration/twin_index.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::registration {
namespace {

using test::PointSet;

std::vector<Eigen::Vector3d> random_queries(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(-55.0, 55.0), z(-2.0, 47.0);
  std::vector<Eigen::Vector3d> q;
  for (int i = 0; i < n; ++i) q.push_back(test::kCentre + Eigen::Vector3d(xy(rng), xy(rng), z(rng)));
  // and points right on the tile borders e = 1200, n = 800
  for (int i = 0; i < n / 4; ++i) q.push_back({1200.0 + 0.01 * (i % 7 - 3), 770.0 + i * 0.3, 0.05 * (i % 5)});
  for (int i = 0; i < n / 4; ++i) q.push_back({1170.0 + i * 0.3, 800.0 + 0.01 * (i % 7 - 3), 0.05 * (i % 5)});
  return q;
}

void expect_same(const std::optional<TwinMatch>& a, const std::optional<TwinMatch>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->p_W, b->p_W);
  EXPECT_EQ(a->n_W, b->n_W);
  EXPECT_EQ(a->distance_m, b->distance_m);
}

TEST(RegistrationTwinIndex, NearestEqualsBruteForceAcrossTileBorders) {
  const PointSet set = test::sample_grid(test::city_surfaces(), 1.0);
  const TwinTileIndex index = test::make_index(set);
  EXPECT_GE(index.tile_count(), 9u);  // the city straddles tile borders
  EXPECT_EQ(index.point_count(), set.p_W.size());
  int found = 0;
  for (const Eigen::Vector3d& q : random_queries(400, 3)) {
    double best = 1.5;
    std::optional<std::size_t> bi;
    for (std::size_t i = 0; i < set.p_W.size(); ++i) {
      const double d = (set.p_W[i] - q).norm();
      if (d <= best) best = d, bi = i;
    }
    const auto m = index.nearest(q, 1.5);
    ASSERT_EQ(m.has_value(), bi.has_value()) << q.transpose();
    if (!m) continue;
    ++found;
    EXPECT_NEAR(m->distance_m, best, 1e-5);  // float storage relative to the tile corner: < 10 um
    EXPECT_NEAR((m->p_W - q).norm(), m->distance_m, 1e-12);
  }
  EXPECT_GT(found, 150);
}

TEST(RegistrationTwinIndex, QueryNearABorderFindsThePointInTheNeighbourTile) {
  TwinTileIndex index(50.0);
  index.add_tile({0, 0}, {{49.9, 10.0, 3.0}}, {{1.0, 0.0, 0.0}});
  index.add_tile({1, 0}, {{95.0, 10.0, 3.0}}, {{1.0, 0.0, 0.0}});
  const auto m = index.nearest({50.1, 10.0, 3.0}, 0.5);  // the query's own tile (1, 0) has nothing this close
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->p_W.x(), 49.9, 1e-5);  // float32 relative to the tile corner
  EXPECT_NEAR(m->distance_m, 0.2, 1e-5);
  EXPECT_FALSE(index.nearest({50.1, 10.0, 3.0}, 0.1).has_value());  // but not beyond max_dist
}

TEST(RegistrationTwinIndex, IncrementalUpdatesEqualAFreshBuild) {
  const auto tiles = test::split_tiles(test::sample_grid(test::city_surfaces(), 1.0));
  ASSERT_GE(tiles.size(), 4u);
  auto it = tiles.begin();
  const twin::TileKey leaving = it->first;
  TwinTileIndex incremental(50.0), fresh(50.0);
  for (const auto& [key, t] : tiles) {
    if (key != tiles.rbegin()->first) incremental.add_tile(key, t.p_W, t.n_W);  // all but the last ...
  }
  incremental.add_tile(tiles.rbegin()->first, tiles.rbegin()->second.p_W, tiles.rbegin()->second.n_W);  // arrives
  EXPECT_TRUE(incremental.remove_tile(leaving));                                                        // leaves
  EXPECT_FALSE(incremental.remove_tile(leaving));
  for (auto r = tiles.rbegin(); r != tiles.rend(); ++r) {  // reverse order: arrival order must not matter
    if (r->first != leaving) fresh.add_tile(r->first, r->second.p_W, r->second.n_W);
  }
  EXPECT_EQ(incremental.keys(), fresh.keys());
  EXPECT_FALSE(incremental.contains(leaving));
  const auto q = random_queries(600, 5);
  const auto a = incremental.nearest_batch(q, 2.0), b = fresh.nearest_batch(q, 2.0);
  ASSERT_EQ(a.size(), q.size());
  int found = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    expect_same(a[i], b[i]);
    found += a[i].has_value();
  }
  EXPECT_GT(found, 200);
}

TEST(RegistrationTwinIndex, BadTilesAreInputErrors) {
  TwinTileIndex index(50.0);
  EXPECT_THROW(index.add_tile({0, 0}, {{1, 2, 3}}, {}), InputError);
  EXPECT_THROW(index.add_tile({0, 0}, {{1, 2, 3}}, {{0, 0, 2}}), InputError);
  EXPECT_THROW(index.add_tile({0, 0}, {{1, 2, NAN}}, {{0, 0, 1}}), InputError);
  EXPECT_THROW(TwinTileIndex(0.0), InputError);
  EXPECT_EQ(index.tile_count(), 0u);
  EXPECT_FALSE(index.nearest({1, 2, 3}, 1.0).has_value());
}

TEST(RegistrationTwinIndex, StoreAndMapTileBytesGiveTheSameIndex) {
  // A 60 m x 60 m ground with one building, as a triangle mesh through `twinslam twin build`'s store writer.
  twin::Mesh mesh;
  auto quad = [&](Eigen::Vector3d o, Eigen::Vector3d u, Eigen::Vector3d v) {
    const int i = static_cast<int>(mesh.p_W.size());
    mesh.p_W.insert(mesh.p_W.end(), {o, o + u, o + u + v, o + v});
    mesh.triangles.push_back({i, i + 1, i + 2});
    mesh.triangles.push_back({i, i + 2, i + 3});
  };
  quad({20, 20, 0}, {60, 0, 0}, {0, 60, 0});
  quad({45, 45, 0}, {10, 0, 0}, {0, 0, 20});
  const auto dir = std::filesystem::temp_directory_path() / ("twinslam_reg_store_" + std::to_string(::getpid()));
  twin::StoreConfig sc;
  sc.point_spacing_m = 1.0;
  const twin::TwinIndex store = twin::build_twin_store(mesh, {47.0, 8.0, 400.0}, sc, dir.string());
  TwinTileIndex from_store(store.tile_size_m), from_bytes(store.tile_size_m);
  const auto keys = tiles_in_window(store, {50.0, 50.0, 0.0}, 150.0);
  EXPECT_EQ(keys.size(), store.tiles.size());
  EXPECT_TRUE(tiles_in_window(store, {500.0, 500.0, 0.0}, 150.0).empty());
  for (const auto& key : keys) {
    add_tile_from_store(from_store, dir.string(), store, key);
    add_tile_from_draco(from_bytes, key, twin::read_tile_file(dir.string(), key, false),
                        twin::read_tile_file(dir.string(), key, true));
  }
  EXPECT_EQ(from_store.point_count(), store.points);
  const auto m = from_store.nearest({50.0, 45.3, 10.0}, 1.0);  // next to the wall y = 45
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->p_W.y(), 45.0, 1e-3);
  EXPECT_NEAR(std::abs(m->n_W.y()), 1.0, 1e-2);
  for (const Eigen::Vector3d& q : random_queries(100, 9)) {
    const Eigen::Vector3d qq = q - test::kCentre + Eigen::Vector3d(50, 50, 0);
    expect_same(from_store.nearest(qq, 2.0), from_bytes.nearest(qq, 2.0));
  }
  EXPECT_THROW(add_tile_from_draco(from_bytes, {0, 0}, {}, {1, 2, 3}), InputError);  // corrupt bytes
  EXPECT_THROW(add_tile_from_draco(from_bytes, {0, 0}, {1, 2, 3}, {}), InputError);  // triangles but no points
  add_tile_from_draco(from_bytes, {9, 9}, {}, {});                                    // an empty tile is fine
  EXPECT_TRUE(from_bytes.contains({9, 9}));
  TwinTileIndex points_only(store.tile_size_m);  // the points-only overload gives the same index
  for (const auto& key : keys) add_tile_from_draco(points_only, key, twin::read_tile_file(dir.string(), key, true));
  for (const Eigen::Vector3d& q : random_queries(50, 10)) {
    const Eigen::Vector3d qq = q - test::kCentre + Eigen::Vector3d(50, 50, 0);
    expect_same(points_only.nearest(qq, 2.0), from_store.nearest(qq, 2.0));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace twinslam::registration
