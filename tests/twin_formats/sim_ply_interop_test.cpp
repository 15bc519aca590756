// The simulator writes its world and twin as PLY (tools/sim/world/src/ply.cpp); the twin loader must read exactly
// that: doubles, per-face building_id and kind, and the twinslam_origin comment that georeferences W.
#include <gtest/gtest.h>

#include "twin_test_utils.hpp"
#include "twinslam/sim/world/mesh.hpp"
#include "twinslam/sim/world/ply.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/ply.hpp"

using namespace twinslam;
using twin_test::Scratch;

TEST(SimPly, TheSimulatorsTwinPlyLoadsWithItsOrigin) {
  Scratch tmp;
  sim::TriMesh world;
  sim::add_box(&world, {-10, -5, 0}, {10, 5, 25.5}, sim::SurfaceKind::kFacade, sim::SurfaceKind::kRoof, 3, true);
  world.add_quad({-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}, sim::SurfaceKind::kGround, sim::kNoBuilding);
  const sim::Origin origin{46.9480, 7.4474, 540.25};
  const std::string path = (tmp / "twin.ply").string();
  sim::write_ply(path, world, origin);

  const twin::PlyFile ply = twin::read_ply(path);
  ASSERT_TRUE(ply.origin.has_value());
  EXPECT_EQ(ply.origin->lat_deg, origin.lat_deg);  // written with 17 significant digits: exact
  EXPECT_EQ(ply.origin->lon_deg, origin.lon_deg);
  EXPECT_EQ(ply.origin->alt_m, origin.alt_m);
  ASSERT_EQ(ply.mesh.num_vertices(), world.p_W.size());
  ASSERT_EQ(ply.mesh.num_triangles(), world.num_triangles());
  for (std::size_t i = 0; i < world.p_W.size(); ++i) EXPECT_EQ(ply.mesh.p_W[i], world.p_W[i]);
  for (std::size_t t = 0; t < world.num_triangles(); ++t) {
    EXPECT_EQ(ply.mesh.triangles[t], world.triangles[t]);
    EXPECT_NEAR(ply.mesh.triangle_area(t), world.area(t), 1e-12);
  }

  // Through the dispatcher at the file's own origin the twin stays where the simulator put it.
  twin::LoadOptions options;
  options.origin = *ply.origin;
  const twin::Mesh loaded = twin::load_twin_source(path, options);
  EXPECT_EQ(loaded.bounds().max(), Eigen::Vector3d(50, 50, 25.5));
  EXPECT_EQ(loaded.bounds().min(), Eigen::Vector3d(-50, -50, 0));
}
