// The ray-traced GNSS model (issue 13): in the open every satellite above the mask is received directly and the fix is
// metres from the truth; beside a tall wall the satellites behind it are lost or arrive reflected (NLOS, longer
// pseudorange) and the fix degrades; the same seed gives the same data; pseudoranges.csv has the contract's columns.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "twinslam/gnss/constellation.hpp"
#include "twinslam/gnss/frames.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/gnss_raytrace.hpp"

namespace twinslam::sim {
namespace {

TriMesh ground() {
  TriMesh m;
  m.add_quad({-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0}, SurfaceKind::kGround, kNoBuilding);
  return m;
}

// A box building x in [x0, x1], y in [-100, 100], h tall (walls counter-clockwise seen from outside).
void add_box(TriMesh* m, double x0, double x1, double h, int id) {
  const double y0 = -100, y1 = 100;
  m->add_quad({x0, y1, 0}, {x0, y0, 0}, {x0, y0, h}, {x0, y1, h}, SurfaceKind::kFacade, id);  // west, normal -x
  m->add_quad({x1, y0, 0}, {x1, y1, 0}, {x1, y1, h}, {x1, y0, h}, SurfaceKind::kFacade, id);  // east, normal +x
  m->add_quad({x1, y1, 0}, {x0, y1, 0}, {x0, y1, h}, {x1, y1, h}, SurfaceKind::kFacade, id);
  m->add_quad({x0, y0, 0}, {x1, y0, 0}, {x1, y0, h}, {x0, y0, h}, SurfaceKind::kFacade, id);
  m->add_quad({x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}, SurfaceKind::kRoof, id);
}

// A street canyon along y: a 20 m building west (x in [-30, -8]) and an 80 m one east (x in [8, 30]). Western
// satellites between ~38 and ~66 deg of elevation are hidden by the west building but reflect off the east one's
// west face over it (NLOS); the low eastern sky is lost.
TriMesh canyon() {
  TriMesh m = ground();
  add_box(&m, -30, -8, 20, 0);
  add_box(&m, 8, 30, 80, 1);
  return m;
}

struct Track {
  std::vector<std::int64_t> stamps;
  std::vector<Eigen::Vector3d> p_W;
};

// 60 s at 5 Hz walking north along x = 0 at 1.5 m height.
Track walk() {
  Track t;
  for (int i = 0; i < 300; ++i) {
    t.stamps.push_back(stamp_ns(0.2 * i));
    t.p_W.emplace_back(0, -60 + 0.4 * i, 1.5);
  }
  return t;
}

double median_horizontal_error(const RaytraceGnss& g) {
  std::vector<double> e;
  for (const GnssSample& s : g.fixes) e.push_back(s.bias_W.head<2>().norm());
  std::sort(e.begin(), e.end());
  return e.empty() ? 1e9 : e[e.size() / 2];
}

TEST(SimGnssRaytrace, InTheOpenEverySatelliteIsDirectAndTheFixIsMetresFromTheTruth) {
  const EmbreeScene world(ground());
  const Track t = walk();
  const Origin origin;
  const RaytraceGnss g = simulate_gnss_raytrace(t.stamps, t.p_W, origin, world, 7);
  ASSERT_EQ(g.epochs, 300u);
  EXPECT_EQ(g.fixes.size(), 300u);
  // As many signals per epoch as satellites above the mask, all of them direct.
  const Eigen::Vector3d rx = gnss::geodetic_to_ecef({origin.lat_deg, origin.lon_deg, origin.alt_m});
  const std::size_t in_view = gnss::satellites_in_view(gnss::nominal_constellation(), rx, 0, 10).size();
  std::size_t first_epoch = 0;
  for (const PseudorangeRow& r : g.pseudoranges) {
    EXPECT_TRUE(r.line_of_sight);
    first_epoch += r.stamp_ns == stamp_ns(0) ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(first_epoch), static_cast<double>(in_view), 1.0);
  EXPECT_LT(median_horizontal_error(g), 3.0);
  EXPECT_GT(median_horizontal_error(g), 0.05);  // the model has errors: atmosphere, noise, clock
}

TEST(SimGnssRaytrace, InAStreetCanyonSignalsAreLostOrReflectedAndTheFixDegrades) {
  const Track t = walk();
  const EmbreeScene open(ground()), street(canyon());
  const RaytraceGnss a = simulate_gnss_raytrace(t.stamps, t.p_W, Origin{}, open, 7);
  const RaytraceGnss b = simulate_gnss_raytrace(t.stamps, t.p_W, Origin{}, street, 7);
  EXPECT_LT(b.pseudoranges.size(), a.pseudoranges.size());
  std::size_t nlos = 0;
  for (const PseudorangeRow& r : b.pseudoranges) nlos += r.line_of_sight ? 0 : 1;
  EXPECT_GT(nlos, 0u);
  // NLOS signals are weaker than the direct ones of the open run.
  double cn0_nlos = 0, cn0_open = 0;
  for (const PseudorangeRow& r : b.pseudoranges) cn0_nlos += r.line_of_sight ? 0 : r.cn0_dbhz / static_cast<double>(nlos);
  for (const PseudorangeRow& r : a.pseudoranges) cn0_open += r.cn0_dbhz / static_cast<double>(a.pseudoranges.size());
  EXPECT_LT(cn0_nlos, cn0_open - 3);
  EXPECT_GT(median_horizontal_error(b), median_horizontal_error(a));
}

TEST(SimGnssRaytrace, TheSameSeedGivesTheSameDataAndAnotherSeedOther) {
  const Track t = walk();
  const EmbreeScene world(canyon());
  const RaytraceGnss a = simulate_gnss_raytrace(t.stamps, t.p_W, Origin{}, world, 7);
  const RaytraceGnss b = simulate_gnss_raytrace(t.stamps, t.p_W, Origin{}, world, 7);
  const RaytraceGnss c = simulate_gnss_raytrace(t.stamps, t.p_W, Origin{}, world, 8);
  ASSERT_EQ(a.pseudoranges.size(), b.pseudoranges.size());
  for (std::size_t i = 0; i < a.pseudoranges.size(); ++i) {
    EXPECT_EQ(a.pseudoranges[i].pseudorange_m, b.pseudoranges[i].pseudorange_m);
  }
  EXPECT_NE(a.pseudoranges[0].pseudorange_m, c.pseudoranges[0].pseudorange_m);
}

}  // namespace
}  // namespace twinslam::sim
