// Ear clipping with holes: the triangles must tile the polygon exactly (area preserved, all inside, normals agree).
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "twinslam/twin/polygon_triangulation.hpp"

using namespace twinslam::twin;

namespace {

struct Poly {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> rings;
  std::vector<int> add_ring(const std::vector<Eigen::Vector2d>& xy) {
    std::vector<int> ring;
    for (const auto& p : xy) {
      ring.push_back(static_cast<int>(points.size()));
      points.emplace_back(p.x(), p.y(), 0.0);
    }
    rings.push_back(ring);
    return ring;
  }
};

double area_of(const std::vector<Eigen::Vector3d>& pts, const std::vector<Eigen::Vector3i>& tris,
               const Eigen::Vector3d& expected_normal, int* wrong_side) {
  double area = 0.0;
  *wrong_side = 0;
  for (const auto& t : tris) {
    const Eigen::Vector3d n = (pts[t[1]] - pts[t[0]]).cross(pts[t[2]] - pts[t[0]]);
    area += 0.5 * n.norm();
    if (n.dot(expected_normal) <= 0) ++*wrong_side;
  }
  return area;
}

// Polygon area with holes by the shoelace formula in the xy plane.
double shoelace(const Poly& poly) {
  double total = 0.0;
  for (std::size_t r = 0; r < poly.rings.size(); ++r) {
    double s = 0.0;
    const auto& ring = poly.rings[r];
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const auto& a = poly.points[ring[i]];
      const auto& b = poly.points[ring[(i + 1) % ring.size()]];
      s += a.x() * b.y() - b.x() * a.y();
    }
    total += (r == 0 ? 1.0 : -1.0) * std::abs(s) / 2.0;
  }
  return total;
}

void expect_exact_tiling(const Poly& poly, std::size_t expected_triangles) {
  const auto tris = triangulate_polygon(poly.points, poly.rings);
  int wrong = 0;
  EXPECT_NEAR(area_of(poly.points, tris, Eigen::Vector3d::UnitZ(), &wrong), shoelace(poly), 1e-9);
  EXPECT_EQ(wrong, 0);
  // n vertices (holes bridged: + 2 per hole) give n - 2 triangles, fewer where bridges line up collinear vertices.
  EXPECT_LE(tris.size(), expected_triangles);
  EXPECT_GE(tris.size() + poly.rings.size(), expected_triangles);
}

}  // namespace

TEST(PolygonTriangulation, SquareWithSquareHole) {
  Poly p;
  p.add_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  p.add_ring({{4, 4}, {6, 4}, {6, 6}, {4, 6}});  // counter-clockwise like the outer: the code must flip it
  expect_exact_tiling(p, 8);
  EXPECT_NEAR(shoelace(p), 96.0, 1e-12);
}

TEST(PolygonTriangulation, SquareWithThreeHolesInARow) {
  Poly p;
  p.add_ring({{0, 0}, {20, 0}, {20, 6}, {0, 6}});
  p.add_ring({{2, 2}, {2, 4}, {4, 4}, {4, 2}});
  p.add_ring({{8, 2}, {8, 4}, {10, 3}});
  p.add_ring({{14, 2}, {14, 4}, {16, 4}, {16, 2}});  // holes at the same height: the bridges must not cross
  expect_exact_tiling(p, 4 + 11 + 2 * 3 - 2);
}

TEST(PolygonTriangulation, ConcaveLAndUShapes) {
  Poly l;
  l.add_ring({{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 8}, {0, 8}});
  expect_exact_tiling(l, 4);
  EXPECT_NEAR(shoelace(l), 12 + 12, 1e-12);
  Poly u;
  u.add_ring({{0, 0}, {9, 0}, {9, 9}, {6, 9}, {6, 3}, {3, 3}, {3, 9}, {0, 9}});
  expect_exact_tiling(u, 6);
  // Clockwise input and collinear vertices along the bottom edge.
  Poly c;
  c.add_ring({{0, 9}, {3, 9}, {3, 3}, {6, 3}, {6, 9}, {9, 9}, {9, 0}, {6, 0}, {3, 0}, {0, 0}});
  const auto tris = triangulate_polygon(c.points, c.rings);
  int wrong = 0;
  EXPECT_NEAR(area_of(c.points, tris, -Eigen::Vector3d::UnitZ(), &wrong), 81 - 18, 1e-9);
  EXPECT_EQ(wrong, 0);  // wound like the (clockwise) outer ring
}

TEST(PolygonTriangulation, TiltedPlaneInFarCoordinatesKeepsAreaAndNormal) {
  // A wall with a window, 85 km east / 447 km north (RD-like coordinates), vertical plane.
  Poly p;
  p.add_ring({{0, 0}, {8, 0}, {8, 5}, {0, 5}});
  p.add_ring({{2, 1}, {2, 3}, {4, 3}, {4, 1}});
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                            Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (auto& q : p.points) q = R * q + Eigen::Vector3d(84616.468, 447422.999, 3.5);
  const auto tris = triangulate_polygon(p.points, p.rings);
  int wrong = 0;
  EXPECT_NEAR(area_of(p.points, tris, R * Eigen::Vector3d::UnitZ(), &wrong), 40 - 4, 1e-6);
  EXPECT_EQ(wrong, 0);
}

TEST(PolygonTriangulation, RandomStarPolygonsWithHolesPreserveArea) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> radius(5.0, 10.0);
  for (int trial = 0; trial < 50; ++trial) {
    Poly p;
    std::vector<Eigen::Vector2d> star;
    const int n = 5 + trial % 30;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      const double r = radius(rng);
      star.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    p.add_ring(star);
    // Small holes near the centre (inside the kernel radius 5 * cos(pi / 5) > 4 of every star).
    p.add_ring({{-3, -1}, {-1, -1}, {-1, 1}, {-3, 1}});
    p.add_ring({{1, -1}, {2.5, 0}, {1, 1}});
    expect_exact_tiling(p, static_cast<std::size_t>(n + 4 + 3 + 4 - 2));
  }
}

TEST(PolygonTriangulation, DegenerateInputGivesNothing) {
  Poly line;
  line.add_ring({{0, 0}, {1, 0}, {2, 0}});
  EXPECT_TRUE(triangulate_polygon(line.points, line.rings).empty());
  Poly twice;
  twice.add_ring({{0, 0}, {0, 0}, {1, 1}});
  EXPECT_TRUE(triangulate_polygon(twice.points, twice.rings).empty());
  Poly bad;
  bad.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  bad.rings = {{0, 1, 7}};
  EXPECT_TRUE(triangulate_polygon(bad.points, bad.rings).empty());
}

TEST(PolygonTriangulation, SelfIntersectingAndRandomGarbageTerminatesWithValidIndices) {
  // Invalid input (bow ties, random point soup, holes outside the outer ring) must never hang or index out of range.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-10.0, 10.0);
  for (int trial = 0; trial < 200; ++trial) {
    Poly p;
    std::vector<Eigen::Vector2d> outer, hole;
    for (int i = 0; i < 3 + trial % 17; ++i) outer.emplace_back(coord(rng), coord(rng));
    for (int i = 0; i < 3 + trial % 5; ++i) hole.emplace_back(coord(rng), coord(rng));
    p.add_ring(outer);
    if (trial % 2 == 0) p.add_ring(hole);
    const auto tris = triangulate_polygon(p.points, p.rings);
    EXPECT_LE(tris.size(), p.points.size() + 2 * p.rings.size());
    for (const auto& t : tris)
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(t[k] >= 0 && t[k] < static_cast<int>(p.points.size()));
  }
}
