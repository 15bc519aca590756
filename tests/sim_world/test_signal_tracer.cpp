// GNSS signal tracer (issue 13, gnss.model: raytrace): line of sight, single-bounce facade reflections by the mirror-
// image method, and the rejections (no reflector, reflector too far, a blocked leg), on hand-built street canyons whose
// geometry is worked out below; then the facade grid against a one-cell grid on a procedural city.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/signal_tracer.hpp"

namespace twinslam::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Unit vector toward a satellite at elevation / azimuth (from north, clockwise) [deg], in W = ENU.
Eigen::Vector3d toward(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), std::sin(e)};
}

// A street canyon along y: ground z = 0 over [-300, 300]^2; building 0 ("A") x in [-30, -10], building 1 ("B")
// x in [10, 30], both y in [-20, 20]. The receiver stands at (0, 0, 1.5): 10 m from each wall. B's west facade
// (x = 10, normal -x) faces the receiver and any satellite in the west.
TriMesh canyon(double height_a_m, double height_b_m = 20, double south_b_m = -20) {
  TriMesh m;
  m.add_quad({-300, -300, 0}, {300, -300, 0}, {300, 300, 0}, {-300, 300, 0}, SurfaceKind::kGround, kNoBuilding);
  add_box(&m, {-30, -20, 0}, {-10, 20, height_a_m}, SurfaceKind::kFacade, SurfaceKind::kRoof, 0);
  if (height_b_m > 0) {
    add_box(&m, {10, south_b_m, 0}, {30, 20, height_b_m}, SurfaceKind::kFacade, SurfaceKind::kRoof, 1);
  }
  return m;
}

const Eigen::Vector3d kReceiver_W(0, 0, 1.5);

// The reflecting geometry of the canyon tests: a satellite 30 deg high, 20 deg north of west (azimuth 290 deg).
// Direct ray: it reaches A's wall (x = -10) after 10 / cos(20 deg) m horizontally, at z = 1.5 + 10 tan(30) / cos(20)
// = 7.64 m. Mirror image of the receiver in B's wall: (20, 0, 1.5); its ray reaches x = 10 at y = 10 tan(20) = 3.64,
// z = 7.64 (the reflection point), and x = -10 at z = 1.5 + 30 tan(30) / cos(20) = 19.93 m. So A blocks the direct
// path for heights in (7.64, 19.93) and the reflected leg above 19.93 m.
constexpr double kElevation_deg = 30, kWestOffset_deg = 20;

TEST(SimWorldSignalTracer, SatelliteStraightUpInTheOpenIsInLineOfSight) {
  const EmbreeScene scene(canyon(12));
  const SignalTracer tracer(scene);
  const SignalPath path = tracer.trace(kReceiver_W, Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(path.line_of_sight);
  EXPECT_FALSE(path.reflected);
  EXPECT_EQ(path.extra_path_m, 0.0);
  EXPECT_EQ(path.building, -1);
  // Straight up from inside building A's footprint under its roof: the roof blocks it.
  EXPECT_FALSE(tracer.trace({-20, 0, 5}, Eigen::Vector3d::UnitZ()).line_of_sight);
}

TEST(SimWorldSignalTracer, SatelliteBehindABuildingIsBlocked) {
  const EmbreeScene scene(canyon(12));
  const SignalTracer tracer(scene);
  const Eigen::Vector3d west_low = toward(10, 270);  // crosses A's wall at z = 1.5 + 10 tan(10) = 3.3 m < 12 m
  EXPECT_FALSE(tracer.trace(kReceiver_W, west_low).line_of_sight);
  // The same direction 60 m north, clear of both buildings, is free: the block above is A, not the tracer.
  EXPECT_TRUE(tracer.trace({0, 60, 1.5}, west_low).line_of_sight);
  // Higher than A's roof seen from the receiver (atan(10.5 / 10) = 46.4 deg): free again.
  EXPECT_TRUE(tracer.trace(kReceiver_W, toward(50, 270)).line_of_sight);
}

TEST(SimWorldSignalTracer, ReflectionExtraPathMatchesTheMirrorGeometry) {
  const EmbreeScene scene(canyon(12));
  const SignalTracer tracer(scene);
  const Eigen::Vector3d s = toward(kElevation_deg, 270 + kWestOffset_deg);
  const SignalPath path = tracer.trace(kReceiver_W, s);
  ASSERT_FALSE(path.line_of_sight);
  ASSERT_TRUE(path.reflected);
  EXPECT_EQ(path.building, 1);
  // 2 h cos(angle between s and B's normal -x), h = 10 m; cos = cos(elevation) cos(azimuth offset from west).
  const double cos_angle = std::cos(kElevation_deg * kDeg) * std::cos(kWestOffset_deg * kDeg);
  EXPECT_NEAR(path.extra_path_m, 2 * 10 * cos_angle, 1e-3);
  // The reflection point: on B's wall plane x = 10, where the mirror image's ray crosses it (worked out above).
  EXPECT_NEAR(path.reflection_point_W.x(), 10.0, 1e-9);
  EXPECT_NEAR(path.reflection_point_W.y(), 10 * std::tan(kWestOffset_deg * kDeg), 1e-3);
  EXPECT_NEAR(path.reflection_point_W.z(),
              1.5 + 10 * std::tan(kElevation_deg * kDeg) / std::cos(kWestOffset_deg * kDeg), 1e-3);
  // Independent of the far-satellite formula: the bounce path to a satellite 20 000 km away, minus the direct range.
  const double range_m = 2e7;
  const Eigen::Vector3d sat_W = kReceiver_W + range_m * s;
  const double bounce_m = (path.reflection_point_W - kReceiver_W).norm() + (sat_W - path.reflection_point_W).norm();
  EXPECT_NEAR(bounce_m - range_m, path.extra_path_m, 1e-3);
}

TEST(SimWorldSignalTracer, LineOfSightWithAFacadeReflectionIsMultipathOnlyWhenAsked) {
  // A only 1 m tall: the direct ray passes over it, and B's wall still reflects the same bounce as above.
  const EmbreeScene scene(canyon(1));
  const SignalTracer tracer(scene);
  const Eigen::Vector3d s = toward(kElevation_deg, 270 + kWestOffset_deg);
  const SignalPath direct_only = tracer.trace(kReceiver_W, s);
  EXPECT_TRUE(direct_only.line_of_sight);
  EXPECT_FALSE(direct_only.reflected);
  const SignalPath both = tracer.trace(kReceiver_W, s, /*also_with_line_of_sight=*/true);
  EXPECT_TRUE(both.line_of_sight);
  ASSERT_TRUE(both.reflected);
  EXPECT_NEAR(both.extra_path_m, 2 * 10 * std::cos(kElevation_deg * kDeg) * std::cos(kWestOffset_deg * kDeg), 1e-3);
  // Straight up nothing reflects (no wall faces the sky), whatever is asked.
  EXPECT_FALSE(tracer.trace(kReceiver_W, Eigen::Vector3d::UnitZ(), true).reflected);
}

TEST(SimWorldSignalTracer, BlockedSatelliteWithoutAReflectorIsDropped) {
  const Eigen::Vector3d s = toward(kElevation_deg, 270 + kWestOffset_deg);
  // Only A: its east wall faces the receiver but has the satellite behind it.
  const EmbreeScene only_a(canyon(12, /*height_b_m=*/0));
  const SignalPath path = SignalTracer(only_a).trace(kReceiver_W, s);
  EXPECT_FALSE(path.line_of_sight);
  EXPECT_FALSE(path.reflected);
  EXPECT_EQ(path.extra_path_m, 0.0);
  EXPECT_EQ(path.building, -1);
  // B only 5 m high: the mirror geometry puts the bounce at z = 7.64 m, above its wall, where there is nothing to
  // reflect off (both legs through that point are clear, so only the facade's extent can refuse it).
  const EmbreeScene low_b(canyon(12, /*height_b_m=*/5));
  const SignalPath over = SignalTracer(low_b).trace(kReceiver_W, s);
  EXPECT_FALSE(over.line_of_sight);
  EXPECT_FALSE(over.reflected);
}

TEST(SimWorldSignalTracer, ReflectionWhoseReflectedLegIsBlockedIsRejected) {
  // A raised to 25 m: the leg from B's wall toward the satellite crosses A's wall at 19.93 m, below its roof.
  const EmbreeScene scene(canyon(25));
  const SignalTracer tracer(scene);
  const SignalPath path = tracer.trace(kReceiver_W, toward(kElevation_deg, 270 + kWestOffset_deg));
  EXPECT_FALSE(path.line_of_sight);
  EXPECT_FALSE(path.reflected);
  EXPECT_EQ(path.building, -1);
}

TEST(SimWorldSignalTracer, ReflectionBehindAnObstacleOnTheReceiverLegIsRejected) {
  // A pole box in the street across the segment receiver (0, 0, 1.5) -> reflection point (10, 3.64, 7.64), which
  // passes x = 5 at y = 1.82, z = 4.57; the direct ray heads west and the reflected leg passes x = 5 at y = 5.46.
  TriMesh m = canyon(12);
  add_box(&m, {4, 0, 0}, {6, 3, 10}, SurfaceKind::kDetail, SurfaceKind::kDetail, kNoBuilding);
  const EmbreeScene scene(m);
  const SignalTracer tracer(scene);
  const SignalPath path = tracer.trace(kReceiver_W, toward(kElevation_deg, 270 + kWestOffset_deg));
  EXPECT_FALSE(path.line_of_sight);
  EXPECT_FALSE(path.reflected);
}

TEST(SimWorldSignalTracer, FacadesBeyondTheMaxDistanceAreIgnored) {
  const EmbreeScene scene(canyon(12));  // B's wall is 10 m from the receiver
  const Eigen::Vector3d s = toward(kElevation_deg, 270 + kWestOffset_deg);
  SignalTracerConfig near;
  near.max_reflection_distance_m = 8;
  EXPECT_FALSE(SignalTracer(scene, near).trace(kReceiver_W, s).reflected);
  near.max_reflection_distance_m = 12;
  EXPECT_TRUE(SignalTracer(scene, near).trace(kReceiver_W, s).reflected);
}

TEST(SimWorldSignalTracer, LongFacadeReachingFromOutsideTheSearchWindowIsFound) {
  // B's west wall runs from y = -250 to 20: its two triangles start 10 grid cells south of the receiver's 150 m
  // window, and must still be found from the cells of the window they cover.
  const EmbreeScene scene(canyon(12, 20, /*south_b_m=*/-250));
  const SignalPath path = SignalTracer(scene).trace(kReceiver_W, toward(kElevation_deg, 270 + kWestOffset_deg));
  ASSERT_TRUE(path.reflected);
  EXPECT_EQ(path.building, 1);
  EXPECT_NEAR(path.reflection_point_W.x(), 10.0, 1e-9);
}

TEST(SimWorldSignalTracer, IndexesOnlyNearVerticalFacadesOfSufficientArea) {
  TriMesh m = canyon(12);  // 2 boxes x 4 walls x 2 triangles = 16 facade triangles; roofs and ground are not
  m.add_triangle({50, 50, 0}, {60, 50, 0}, {55, 60, 8}, SurfaceKind::kFacade, 2);     // sloped: normal z = 0.78
  m.add_triangle({50, 70, 0}, {50.5, 70, 0}, {50.5, 70, 1}, SurfaceKind::kFacade, 2);  // vertical, 0.25 m^2
  const EmbreeScene scene(m);
  EXPECT_EQ(SignalTracer(scene).num_facades(), 16u);
  SignalTracerConfig small;
  small.min_facade_area_m2 = 0.1;
  EXPECT_EQ(SignalTracer(scene, small).num_facades(), 17u);
}

TEST(SimWorldSignalTracer, GridGivesTheSameAnswersAsOneCellOnACity) {
  CityConfig config;
  config.size_m = 300;
  const EmbreeScene scene(build_city(config, 11).mesh);
  SignalTracerConfig one_cell;
  one_cell.grid_cell_m = 1e5;  // every facade in one cell: a brute-force scan
  const SignalTracer grid(scene), brute(scene, one_cell);
  Eigen::Vector3d lo, hi;
  scene.mesh().bounds(&lo, &hi);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(lo.x(), hi.x()), uy(lo.y(), hi.y()), uz(1.5, 30), uaz(0, 360),
      uel(5, 60);
  int reflected = 0, sight = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p(ux(rng), uy(rng), uz(rng)), s = toward(uel(rng), uaz(rng));
    const SignalPath a = grid.trace(p, s), b = brute.trace(p, s);
    ASSERT_EQ(a.line_of_sight, b.line_of_sight) << i;
    ASSERT_EQ(a.reflected, b.reflected) << i;
    ASSERT_EQ(a.building, b.building) << i;
    ASSERT_EQ(a.extra_path_m, b.extra_path_m) << i;
    reflected += a.reflected;
    sight += a.line_of_sight;
    if (a.reflected) {
      EXPECT_GT(a.extra_path_m, 0.0);
      EXPECT_LE(a.extra_path_m, 2 * config.size_m);
    }
  }
  EXPECT_GT(reflected, 20);  // the comparison is not between two empty answers
  EXPECT_GT(sight, 200);
}

}  // namespace
}  // namespace twinslam::sim
