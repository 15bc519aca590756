// The geometry under twin-change detection: closest point on a triangle (mesh.hpp), segment crossings, convex hull.
#include <gtest/gtest.h>

#include "changes_geometry.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin::detail {
namespace {

using twin::closest_point_on_triangle;

const Eigen::Vector3d kA(0, 0, 0), kB(4, 0, 0), kC(0, 4, 0);

TEST(ChangesGeometry, ClosestPointOnATriangleFromEachRegion) {
  EXPECT_TRUE(closest_point_on_triangle({1, 1, 3}, kA, kB, kC).isApprox(Eigen::Vector3d(1, 1, 0)));    // face
  EXPECT_TRUE(closest_point_on_triangle({-2, -2, 1}, kA, kB, kC).isApprox(kA));                       // vertex a
  EXPECT_TRUE(closest_point_on_triangle({6, -1, 0}, kA, kB, kC).isApprox(kB));                        // vertex b
  EXPECT_TRUE(closest_point_on_triangle({2, -3, 0}, kA, kB, kC).isApprox(Eigen::Vector3d(2, 0, 0)));  // edge ab
  EXPECT_TRUE(closest_point_on_triangle({3, 3, 0}, kA, kB, kC).isApprox(Eigen::Vector3d(2, 2, 0)));   // edge bc
}

TEST(ChangesGeometry, SegmentCrossesATriangleOnlyBetweenItsEnds) {
  const auto t = segment_crosses({1, 1, -1}, {1, 1, 3}, kA, kB, kC);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.25, 1e-12);
  EXPECT_FALSE(segment_crosses({1, 1, 1}, {1, 1, 3}, kA, kB, kC));    // ends before the plane
  EXPECT_FALSE(segment_crosses({5, 5, -1}, {5, 5, 1}, kA, kB, kC));   // misses the triangle
  EXPECT_FALSE(segment_crosses({-1, 1, 0}, {5, 1, 0}, kA, kB, kC));   // in its plane
}

TEST(ChangesGeometry, ConvexHullIsCounterClockwiseWithoutInnerOrCollinearPoints) {
  const std::vector<Eigen::Vector2d> hull =
      convex_hull({{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 2}, {1, 3}, {4, 4}});
  ASSERT_EQ(hull.size(), 4u);
  double area = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    area += p.x() * q.y() - q.x() * p.y();
  }
  EXPECT_NEAR(area / 2, 16.0, 1e-12);  // positive: counter-clockwise
}

TEST(ChangesGeometry, GridReturnsEachNearbyTriangleOnce) {
  Mesh m;
  m.p_W = {{-50, -50, 0}, {50, -50, 0}, {0, 50, 0}, {10, 10, 0}, {11, 10, 0}, {10, 11, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const TriangleGrid grid(m, 4.0);
  EXPECT_EQ(grid.near({9, 9}, {12, 12}), (std::vector<int>{0, 1}));  // the big one spans many cells: once
  EXPECT_EQ(grid.near({-40, -40}, {-39, -39}), (std::vector<int>{0}));
  EXPECT_TRUE(grid.near({200, 200}, {201, 201}).empty());
}

}  // namespace
}  // namespace twinslam::twin::detail
