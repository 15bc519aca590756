// PLY: the world mesh survives a write/read round trip bit for bit, with its georeference; bad files -> InputError.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/ply.hpp"

namespace twinslam::sim {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("twinslam_sim_world_" + name)).string();
}

TEST(SimWorldPly, RoundTripIsExactIncludingOrigin) {
  CityConfig config;
  config.size_m = 200;
  const City city = build_city(config, 3);
  const Origin origin{47.376912345678901, 8.541698765432101, 408.125};
  const std::string path = temp_path("roundtrip.ply");
  write_ply(path, city.mesh, origin);
  const PlyMesh back = read_ply(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(back.has_origin);
  EXPECT_EQ(back.origin.lat_deg, origin.lat_deg);
  EXPECT_EQ(back.origin.lon_deg, origin.lon_deg);
  EXPECT_EQ(back.origin.alt_m, origin.alt_m);
  ASSERT_EQ(back.mesh.p_W.size(), city.mesh.p_W.size());
  ASSERT_EQ(back.mesh.num_triangles(), city.mesh.num_triangles());
  for (std::size_t i = 0; i < city.mesh.p_W.size(); ++i) ASSERT_EQ(back.mesh.p_W[i], city.mesh.p_W[i]) << i;
  EXPECT_EQ(back.mesh.triangles, city.mesh.triangles);
  EXPECT_EQ(back.mesh.building_id, city.mesh.building_id);
  EXPECT_EQ(back.mesh.kind, city.mesh.kind);
}

TEST(SimWorldPly, MissingFileNamesTheFile) {
  try {
    read_ply("/nonexistent/twin.ply");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/twin.ply"), std::string::npos) << e.what();
  }
}

TEST(SimWorldPly, AsciiAndTruncatedFilesAreRejected) {
  const std::string ascii = temp_path("ascii.ply");
  std::ofstream(ascii) << "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
  EXPECT_THROW(read_ply(ascii), InputError);
  std::filesystem::remove(ascii);

  TriMesh mesh;
  add_box(&mesh, {0, 0, 0}, {1, 1, 1}, SurfaceKind::kFacade, SurfaceKind::kRoof, 0);
  const std::string cut = temp_path("cut.ply");
  write_ply(cut, mesh, Origin{});
  std::filesystem::resize_file(cut, std::filesystem::file_size(cut) - 7);
  EXPECT_THROW(read_ply(cut), InputError);
  std::filesystem::remove(cut);
}

}  // namespace
}  // namespace twinslam::sim
