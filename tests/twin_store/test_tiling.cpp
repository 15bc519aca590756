// Cutting by the tile grid and the point sampling of the twin store (tiling.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "test_meshes.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/tiling.hpp"

namespace twinslam::twin {
namespace {

double area_of(const std::map<TileKey, Mesh>& tiles) {
  double sum = 0;
  for (const auto& [key, m] : tiles) sum += m.total_area();
  return sum;
}

TEST(TwinTiling, CutPreservesAreaAndKeepsEveryPieceInsideItsTile) {
  // Ground cells of 17.3 m from (-73, -41): cell edges never coincide with the 50 m grid, boxes straddle it.
  const Mesh city = test::box_city(-73.0, -41.0, 12, 17.3, 25, 3);
  const double s = 50.0;
  const auto tiles = cut_into_tiles(city, s);
  EXPECT_NEAR(area_of(tiles), city.total_area(), 1e-9 * city.total_area());
  std::size_t triangles = 0;
  for (const auto& [key, m] : tiles) {
    ASSERT_FALSE(m.triangles.empty()) << "empty tile " << key.str() << " stored";
    triangles += m.num_triangles();
    for (const Eigen::Vector3d& p : m.p_W) {
      EXPECT_GE(p.x(), key.ix * s - 1e-9) << key.str();
      EXPECT_LE(p.x(), (key.ix + 1) * s + 1e-9) << key.str();
      EXPECT_GE(p.y(), key.iy * s - 1e-9) << key.str();
      EXPECT_LE(p.y(), (key.iy + 1) * s + 1e-9) << key.str();
    }
  }
  EXPECT_GT(triangles, city.num_triangles());  // triangles crossing grid lines were cut
  // 12 * 17.3 = 207.6 m from -73 and -41: e tiles -2..2, n tiles -1..3, all with ground.
  EXPECT_EQ(tiles.size(), 25u);
  const Eigen::AlignedBox3d b = city.bounds();
  EXPECT_EQ(tiles.begin()->first, tile_of(b.min().x(), b.min().y(), s));
}

TEST(TwinTiling, LargeTriangleSplitsOverAllTilesItCoversHeightsNeverCut) {
  Mesh m;
  m.p_W = {{-10, -10, 0}, {140, -10, 30}, {-10, 140, 400}};  // spans tiles -1..2 of 50 m both ways, 400 m tall
  m.triangles = {{0, 1, 2}};
  const auto tiles = cut_into_tiles(m, 50.0);
  EXPECT_NEAR(area_of(tiles), m.total_area(), 1e-9 * m.total_area());
  // Of the 4 x 4 candidate tiles, the hypotenuse e + n = 130 leaves (1, 2), (2, 1), (2, 2) empty: 13 tiles.
  EXPECT_EQ(tiles.size(), 13u);
  EXPECT_TRUE(tiles.count(TileKey{-1, -1}) && tiles.count(TileKey{1, 1}) && tiles.count(TileKey{2, 0}));
  EXPECT_FALSE(tiles.count(TileKey{2, 1}) || tiles.count(TileKey{1, 2}) || tiles.count(TileKey{2, 2}));
  // Normals of the pieces are the triangle's: clipping keeps the winding.
  for (const auto& [key, t] : tiles) {
    for (std::size_t i = 0; i < t.num_triangles(); ++i)
      EXPECT_GT(t.triangle_normal(i).dot(m.triangle_normal(0)), 0.999999);
  }
}

TEST(TwinTiling, FacadeOnAGridLineGoesToExactlyOneTile) {
  Mesh m;  // a wall in the plane e = 50 from n = 10 to 20, 30 m tall
  m.p_W = {{50, 10, 0}, {50, 20, 0}, {50, 20, 30}, {50, 10, 30}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const auto tiles = cut_into_tiles(m, 50.0);
  ASSERT_EQ(tiles.size(), 1u);
  EXPECT_EQ(tiles.begin()->first, (TileKey{1, 0}));  // tile 1 covers e in [50, 100)
  EXPECT_NEAR(tiles.begin()->second.total_area(), 300.0, 1e-9);
  EXPECT_EQ(tiles.begin()->second.num_vertices(), 4u);  // shared corners stay shared
}

TEST(TwinTiling, BadTrianglesAndPositionsAreInputErrors) {
  Mesh m;
  m.p_W = {{0, 0, 0}, {1, 0, 0}};
  m.triangles = {{0, 1, 2}};
  EXPECT_THROW(cut_into_tiles(m, 50.0), InputError);
  m.p_W.emplace_back(std::nan(""), 0, 0);
  EXPECT_THROW(cut_into_tiles(m, 50.0), InputError);
  Mesh points;
  points.p_W = {{0, 0, 0}};  // no normals
  EXPECT_THROW(split_points_into_tiles(points, 50.0), InputError);
}

TEST(TwinSampling, DensityIsOnePerSpacingSquaredAlsoOnTinyTriangles) {
  const double s = 0.5;
  const Mesh coarse = test::box_city(0, 0, 4, 12.5, 6, 9);  // triangles of ~78 m^2 and boxes
  const Mesh fine = test::box_city(0, 0, 250, 0.2, 0, 9);   // 125000 triangles of 0.02 m^2 (0.08 points each)
  for (const Mesh* m : {&coarse, &fine}) {
    const Mesh pts = sample_points(*m, s, 7);
    const double expected = m->total_area() / (s * s);
    EXPECT_NEAR(static_cast<double>(pts.p_W.size()), expected, 0.02 * expected);
    ASSERT_EQ(pts.n_W.size(), pts.p_W.size());
  }
  // Uniform over the area: each quadrant of the fine 50 m x 50 m ground gets a quarter of the points.
  const Mesh pts = sample_points(fine, s, 7);
  int quadrant[4] = {0, 0, 0, 0};
  for (const Eigen::Vector3d& p : pts.p_W) ++quadrant[(p.x() >= 25 ? 1 : 0) + (p.y() >= 25 ? 2 : 0)];
  for (int q : quadrant) EXPECT_NEAR(q, pts.p_W.size() / 4.0, 0.03 * pts.p_W.size() / 4.0);
}

TEST(TwinSampling, PointsLieOnTheirTriangleWithItsNormalAndAreDeterministicPerSeed) {
  Mesh box;
  test::add_box(&box, {0, 0, 0}, {10, 20, 30});
  const Mesh a = sample_points(box, 0.5, 11), b = sample_points(box, 0.5, 11), c = sample_points(box, 0.5, 12);
  ASSERT_EQ(a.p_W.size(), b.p_W.size());
  for (std::size_t i = 0; i < a.p_W.size(); ++i) EXPECT_EQ(a.p_W[i], b.p_W[i]);
  ASSERT_FALSE(c.p_W.empty());
  EXPECT_NE(a.p_W[0], c.p_W[0]);
  const Eigen::Vector3d lo(0, 0, 0), hi(10, 20, 30);
  for (std::size_t i = 0; i < a.p_W.size(); ++i) {
    const Eigen::Vector3d& n = a.n_W[i];
    const Eigen::Vector3d& p = a.p_W[i];
    ASSERT_NEAR(n.norm(), 1.0, 1e-12);
    const int axis = std::abs(n.x()) > 0.5 ? 0 : std::abs(n.y()) > 0.5 ? 1 : 2;
    EXPECT_NEAR(p[axis], n[axis] > 0 ? hi[axis] : lo[axis], 1e-9);  // outward normal of the face the point is on
  }
}

}  // namespace
}  // namespace twinslam::twin
