// The streamer's decisions on a synthetic 50 m grid: which tiles a vehicle gets when it moves (only the new ones,
// never one twice), how vehicles share latched tiles, where the window's edges are, and what a TileRequest returns.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "tile_index_fixture.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/tiles/tile_streamer.hpp"

namespace twinslam::tiles {
namespace {

using twin::TileKey;

std::set<TileKey> as_set(const std::vector<TileKey>& keys) { return {keys.begin(), keys.end()}; }

TEST(TileStreamer, FirstUpdateSendsTheWindowThenOnlyNewTiles) {
  TileStreamer s(test::grid_index(-10, 9), 150.0);
  // At the centre of tile (0, 0) the 150 m window [-50, 100) covers tiles -1..1 in both axes.
  const StreamDecision first = s.update("uav0", {25, 25, 10});
  std::set<TileKey> expected;
  for (int ix = -1; ix <= 1; ++ix)
    for (int iy = -1; iy <= 1; ++iy) expected.insert({ix, iy});
  EXPECT_EQ(as_set(first.new_for_vehicle), expected);
  EXPECT_EQ(first.new_for_vehicle.size(), 9u);
  EXPECT_EQ(first.publish, first.new_for_vehicle);
  EXPECT_EQ(first.publish.front(), (TileKey{0, 0}));  // nearest first: the tile under the vehicle

  // Standing still: nothing new.
  EXPECT_TRUE(s.update("uav0", {25, 25, 12}).new_for_vehicle.empty());
  // 10 m east: the window [-40, 110) now meets column ix = 2.
  const StreamDecision east = s.update("uav0", {35, 25, 10});
  EXPECT_EQ(as_set(east.new_for_vehicle), (std::set<TileKey>{{2, -1}, {2, 0}, {2, 1}}));
  // Back west: column -1 is still held, nothing is sent again.
  EXPECT_TRUE(s.update("uav0", {25, 25, 10}).new_for_vehicle.empty());
}

TEST(TileStreamer, NothingTwiceAlongAPath) {
  TileStreamer s(test::grid_index(-10, 9, {{0, 2}, {3, 3}}), 150.0);
  std::map<TileKey, int> sent;
  // A figure-eight over 200 m, 2000 updates, passing every place several times.
  for (int k = 0; k < 2000; ++k) {
    const double t = k * 0.01;
    const Eigen::Vector3d p(200 * std::sin(t), 100 * std::sin(2 * t), 20);
    for (const TileKey& key : s.update("uav0", p).publish) ++sent[key];
  }
  ASSERT_FALSE(sent.empty());
  for (const auto& [key, n] : sent) EXPECT_EQ(n, 1) << key.ix << "_" << key.iy;
  // Holes (no geometry) are never sent.
  EXPECT_EQ(sent.count({0, 2}), 0u);
  EXPECT_EQ(sent.count({3, 3}), 0u);
}

TEST(TileStreamer, WindowEdges) {
  TileStreamer s(test::grid_index(-10, 9), 100.0);  // half side 50 m
  // At e = 49.9 the window [-0.1, 99.9) reaches into tile -1 by 0.1 m and stops short of tile 2.
  const auto a = as_set(s.update("a", {49.9, 25, 0}).new_for_vehicle);
  EXPECT_TRUE(a.count({-1, 0}));
  EXPECT_TRUE(a.count({1, 0}));
  EXPECT_FALSE(a.count({2, 0}));
  // At e = 50 exactly, [0, 100) starts on tile 0's edge: tile -1 only touches it and is not sent, tile 2 neither.
  const auto b = as_set(s.update("b", {50, 25, 0}).new_for_vehicle);
  EXPECT_FALSE(b.count({-1, 0}));
  EXPECT_TRUE(b.count({0, 0}));
  EXPECT_TRUE(b.count({1, 0}));
  EXPECT_FALSE(b.count({2, 0}));
  // At the grid's border the window holds only stored tiles; far outside the city it holds none.
  const auto c = s.update("c", {490, 490, 0}).new_for_vehicle;
  EXPECT_EQ(as_set(c), (std::set<TileKey>{{8, 8}, {8, 9}, {9, 8}, {9, 9}}));
  EXPECT_TRUE(s.update("d", {1e7, -1e7, 0}).new_for_vehicle.empty());
  EXPECT_TRUE(s.update("e", {std::nan(""), 0, 0}).new_for_vehicle.empty());
}

TEST(TileStreamer, VehiclesShareLatchedTiles) {
  TileStreamer s(test::grid_index(-10, 9), 150.0);
  const StreamDecision a = s.update("uav0", {25, 25, 10});
  EXPECT_EQ(a.publish.size(), 9u);
  // uav1 next to uav0: it needs 9 tiles too, 6 of them already latched on the wire: only 3 are published.
  const StreamDecision b = s.update("uav1", {75, 25, 10});
  EXPECT_EQ(b.new_for_vehicle.size(), 9u);
  EXPECT_EQ(as_set(b.publish), (std::set<TileKey>{{2, -1}, {2, 0}, {2, 1}}));
  EXPECT_TRUE(s.holds("uav1", {0, 0}));
  EXPECT_FALSE(s.holds("uav0", {2, 0}));
  // uav0 moving into uav1's tiles: it needs column 2 but nothing is published twice.
  const StreamDecision a2 = s.update("uav0", {75, 25, 10});
  EXPECT_EQ(as_set(a2.new_for_vehicle), (std::set<TileKey>{{2, -1}, {2, 0}, {2, 1}}));
  EXPECT_TRUE(a2.publish.empty());
  EXPECT_EQ(s.vehicles(), 2u);
  EXPECT_EQ(s.published_count(), 12u);
}

TEST(TileStreamer, FailedPublicationIsRetried) {
  TileStreamer s(test::grid_index(-10, 9), 150.0);
  s.update("uav0", {25, 25, 10});
  s.publish_failed({0, 0});
  EXPECT_FALSE(s.published({0, 0}));
  EXPECT_EQ(s.update("uav0", {25, 25, 11}).publish, (std::vector<TileKey>{{0, 0}}));
}

TEST(TileStreamer, AFailedReSendLeavesTheLatchedTileCountedOnTheWire) {
  // The writer still latches a tile whose re-send failed: it must keep counting against the instance limit, or more
  // tiles than the writer can hold go out (found by fuzzing the tiles handler with failing writes).
  TileStreamer s(test::grid_index(-10, 9), 150.0, 9);
  ASSERT_EQ(s.update("uav0", {25, 25, 10}).publish.size(), 9u);
  const StreamDecision r = s.request("uav0", {25, 25}, 75.0, {});
  ASSERT_EQ(r.publish.size(), 9u);
  for (const TileKey& k : r.publish) s.publish_failed(k);
  EXPECT_EQ(s.published_count(), 9u);
  EXPECT_FALSE(s.holds("uav0", {0, 0}));
  const StreamDecision next = s.update("uav1", {225, 25, 10});  // another window: the writer is full
  EXPECT_TRUE(next.publish.empty());
  EXPECT_EQ(next.over_limit.size(), 9u);
}

TEST(TileStreamer, StopsPublishingAtTheWritersInstanceLimit) {
  TileStreamer s(test::grid_index(-10, 9), 150.0, 12);  // the writer can latch 12 tiles
  EXPECT_EQ(s.update("uav0", {25, 25, 10}).publish.size(), 9u);
  const StreamDecision d = s.update("uav0", {125, 25, 10});  // needs columns 2 and 3: 6 more
  EXPECT_EQ(d.publish.size(), 3u);
  EXPECT_EQ(d.over_limit.size(), 3u);
  EXPECT_EQ(s.published_count(), 12u);
  for (const TileKey& k : d.over_limit) EXPECT_FALSE(s.holds("uav0", k));
  // Latched tiles still reach other vehicles; the ones over the limit stay pending, never half-sent.
  const StreamDecision other = s.update("uav1", {25, 25, 10});
  EXPECT_EQ(other.new_for_vehicle.size(), 9u);
  EXPECT_TRUE(other.publish.empty());
  EXPECT_EQ(s.update("uav0", {125, 25, 11}).over_limit.size(), 3u);
}

TEST(TileStreamer, RequestSendsWhatTheRequesterLacksEvenIfLatched) {
  TileStreamer s(test::grid_index(-10, 9), 150.0);
  s.update("uav0", {25, 25, 10});  // publishes -1..1 x -1..1
  // A restarted client holding only (0, 0) asks for the 100 m window around (50, 50): tiles 0..1 x 0..1.
  const StreamDecision r = s.request("uav0", {50, 50}, 50.0, {{0, 0}});
  EXPECT_EQ(as_set(r.publish), (std::set<TileKey>{{0, 1}, {1, 0}, {1, 1}}));
  EXPECT_EQ(r.publish, r.new_for_vehicle);
  // It now holds exactly what it listed plus what was sent: moving there sends the rest of the 150 m window only.
  EXPECT_FALSE(s.holds("uav0", {-1, -1}));
  const StreamDecision u = s.update("uav0", {25, 25, 10});
  EXPECT_EQ(u.new_for_vehicle.size(), 5u);  // -1 column and row again
  EXPECT_TRUE(u.publish.empty());           // but those are latched on the wire
  // Bad windows are input errors.
  EXPECT_THROW(s.request("uav0", {0, 0}, 0.0, {}), InputError);
  EXPECT_THROW(s.request("uav0", {0, 0}, std::nan(""), {}), InputError);
  EXPECT_THROW(s.request("uav0", {std::nan(""), 0}, 10.0, {}), InputError);
  // A huge window costs at most the grid (400 tiles here) and returns every stored tile not held.
  EXPECT_EQ(s.request("big", {0, 0}, 1e12, {}).publish.size(), 400u);
}

TEST(TileGrid, WireKeysRoundTrip) {
  const TileGrid g(test::grid_index(-2, 2));
  EXPECT_EQ(g.wire_key({-1, 2}), "testtwin/-1_2");
  EXPECT_EQ(g.parse_wire_key("testtwin/-1_2"), (TileKey{-1, 2}));
  EXPECT_EQ(g.parse_wire_key("3_-4"), (TileKey{3, -4}));
  EXPECT_FALSE(g.parse_wire_key("othertwin/1_2"));
  EXPECT_FALSE(g.parse_wire_key("testtwin/1_"));
  EXPECT_FALSE(g.parse_wire_key("testtwin/1x2"));
  EXPECT_FALSE(g.parse_wire_key(""));
  EXPECT_NEAR(g.distance_to_square({0, 0}, {25, 25}), 0.0, 1e-12);
  EXPECT_NEAR(g.distance_to_square({0, 0}, {53, 54}), 5.0, 1e-12);
  // Content bounds come back in W to float precision relative to the tile's corner, even far from the origin.
  const TileGrid far(test::grid_index(100, 101));
  const Eigen::AlignedBox3d b = far.bounds_W(*far.find({101, 100}));
  EXPECT_NEAR(b.min().x(), 5050.0, 1e-5);
  EXPECT_NEAR(b.max().y(), 5050.0, 1e-5);
  EXPECT_NEAR(b.max().z(), 30.0, 1e-5);
  twin::TwinIndex bad = test::grid_index(0, 1);
  bad.tile_size_m = 0;
  EXPECT_THROW(TileGrid{bad}, InputError);
}

TEST(TileGrid, SparseTwinWithoutACellTable) {
  // Two 3 x 3 districts 50 km apart: a dense cell table would need a million cells; lookups still find each tile.
  twin::TwinIndex index = test::grid_index(-1, 1);
  for (const twin::TileInfo& info : test::grid_index(999, 1001).tiles) index.tiles.push_back(info);
  const TileGrid g(index);
  EXPECT_LT(g.memory_bytes(), 4096u);
  EXPECT_NE(g.find({1000, 1001}), nullptr);
  EXPECT_EQ(g.find({500, 500}), nullptr);
  EXPECT_EQ(as_set(g.tiles_in({{50025, 50025}, 75})),
            (std::set<TileKey>{{999, 999}, {999, 1000}, {999, 1001}, {1000, 999}, {1000, 1000}, {1000, 1001},
                               {1001, 999}, {1001, 1000}, {1001, 1001}}));
  EXPECT_EQ(g.tiles_in({{25, 25}, 75}).size(), 9u);
  EXPECT_TRUE(g.tiles_in({{25000, 25000}, 75}).empty());
}

TEST(TileGrid, WindowsBeyondTheIntRangeAreEmptyNotAnEndlessLoop) {
  // A diverged estimate or a forged sample puts the vehicle 10^12 m away: (c - h) / s does not fit an int, and the
  // cast once wrapped the column range to [INT_MIN, INT_MAX] (a hang found by fuzzing the tiles handler).
  const TileGrid g(test::grid_index(-2, 2));
  for (const double c : {1e12, -1e12, 1e300, -1e300}) {
    EXPECT_TRUE(g.tiles_in({{c, 25}, 75}).empty()) << c;
    EXPECT_TRUE(g.tiles_in({{25, c}, 75}).empty()) << c;
  }
  EXPECT_EQ(g.tiles_in({{25, 25}, 1e300}).size(), 25u);  // a huge window around the twin holds all of it
  TileStreamer s(test::grid_index(-2, 2), 150.0);
  EXPECT_TRUE(s.update("uav0", {1e12, 0, 0}).new_for_vehicle.empty());
  EXPECT_EQ(s.update("uav0", {25, 25, 0}).new_for_vehicle.size(), 9u);
}

}  // namespace
}  // namespace twinslam::tiles
