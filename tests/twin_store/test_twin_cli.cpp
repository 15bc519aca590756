// `twinslam twin build / info` end to end (CONTRACTS.md "twinslam twin info --json"), running the built executable.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "test_meshes.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/ply.hpp"
#include "twinslam/sim/world/twin.hpp"
#include "twinslam/twin/ply.hpp"

namespace twinslam::twin {
namespace {

namespace fs = std::filesystem;
using twinslam::test::run_process;

class TwinCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twin_cli_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static twinslam::test::ProcessOutput twinslam(const std::vector<std::string>& args) {
    std::vector<std::string> argv{std::string(TWINSLAM_BIN_DIR) + "/twinslam"};
    argv.insert(argv.end(), args.begin(), args.end());
    return run_process(argv);
  }
  static void expect_bad_input(const twinslam::test::ProcessOutput& r, const std::string& mention) {
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  }
  nlohmann::json info_json(const fs::path& twin) const {
    const auto r = twinslam({"twin", "info", twin.string(), "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }

  fs::path dir_;
};

TEST_F(TwinCli, BuildFromAPlyThenInfoJsonReportsTheContractKeys) {
  const Mesh city = test::box_city(-60.0, -35.0, 9, 15.0, 15, 2);
  const fs::path ply = dir_ / "city.ply", twin = dir_ / "twin";
  write_ply(ply.string(), city, PlyFormat::kBinaryLittleEndian);
  const auto build = twinslam({"twin", "build", ply.string(), "--origin", "47.3769,8.5417,408", "--out", twin.string(),
                               "--tile-size", "40", "--spacing", "0.7"});
  ASSERT_EQ(build.exit_code, 0) << build.out << build.err;
  EXPECT_NE(build.out.find("source " + ply.string() + ": " + std::to_string(city.num_triangles()) + " triangles"),
            std::string::npos)
      << build.out;

  const nlohmann::json j = info_json(twin);
  for (const char* key : {"origin", "tiles", "triangles", "points", "extent_enu"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["origin"], nlohmann::json({47.3769, 8.5417, 408.0}));
  EXPECT_GE(j["triangles"].get<std::size_t>(), city.num_triangles());
  const double expected_points = city.total_area() / (0.7 * 0.7);
  EXPECT_NEAR(j["points"].get<double>(), expected_points, 0.02 * expected_points);
  // 135 m from -60 and -35 in 40 m tiles: e tiles -2..1, n tiles -1..2.
  EXPECT_EQ(j["tiles"].get<int>(), 16);
  const Eigen::AlignedBox3d b = city.bounds();
  const std::vector<double> extent = j["extent_enu"];
  const std::vector<double> source = {b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z()};
  ASSERT_EQ(extent.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(extent[k], source[k]) << k;

  const auto text = twinslam({"twin", "info", twin.string(), "--preview", (dir_ / "top.png").string()});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("tiles 16"), std::string::npos) << text.out;
  std::ifstream png(dir_ / "top.png", std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST_F(TwinCli, TheSimulatorsTwinPlyBuilds) {
  // What `twinslam sim` writes into DIR/twin/twin.ply, made here without rendering a flight.
  sim::CityConfig config;
  config.size_m = 150;
  const sim::City city = sim::build_city(config, 4);
  const sim::Twin derived = sim::derive_twin(city, sim::TwinConfig{}, 4);
  const fs::path ply = dir_ / "twin.ply", twin = dir_ / "store";
  sim::write_ply(ply.string(), derived.mesh, sim::Origin{});
  const auto build =
      twinslam({"twin", "build", ply.string(), "--origin", "47.3769,8.5417,408.0", "--out", twin.string()});
  ASSERT_EQ(build.exit_code, 0) << build.out << build.err;
  const nlohmann::json j = info_json(twin);
  EXPECT_GE(j["triangles"].get<std::size_t>(), derived.mesh.num_triangles());
  Eigen::Vector3d lo, hi;
  derived.mesh.bounds(&lo, &hi);
  EXPECT_NEAR(j["extent_enu"][0].get<double>(), lo.x(), 1e-9);
  EXPECT_NEAR(j["extent_enu"][5].get<double>(), hi.z(), 1e-9);
}

TEST_F(TwinCli, BadUsageAndInputExitTwoWithOneLine) {
  Mesh box;
  test::add_box(&box, {0, 0, 0}, {5, 5, 5});
  const fs::path ply = dir_ / "box.ply", twin = dir_ / "twin";
  write_ply(ply.string(), box, PlyFormat::kAscii);
  expect_bad_input(twinslam({"twin", "build", ply.string(), "--origin", "47.3,abc,1", "--out", twin.string()}),
                   "origin");
  expect_bad_input(twinslam({"twin", "build", ply.string(), "--origin", "95,8,1", "--out", twin.string()}), "latitude");
  expect_bad_input(
      twinslam({"twin", "build", (dir_ / "nope.ply").string(), "--origin", "47,8,400", "--out", twin.string()}),
      "nope.ply");
  expect_bad_input(
      twinslam({"twin", "build", ply.string(), "--origin", "47,8,400", "--out", twin.string(), "--tile-size", "0"}),
      "tile size");
  expect_bad_input(twinslam({"twin", "info", (dir_ / "missing").string()}), "index.json");
  Mesh points;  // a point set with normals cannot be merged into a triangle mesh
  points.p_W = {{1, 1, 1}, {2, 2, 2}};
  points.n_W = {{0, 0, 1}, {0, 0, 1}};
  write_ply((dir_ / "points.ply").string(), points, PlyFormat::kAscii);
  expect_bad_input(twinslam({"twin", "build", ply.string(), (dir_ / "points.ply").string(), "--origin", "47,8,400",
                             "--out", twin.string()}),
                   "cannot combine");
  EXPECT_EQ(twinslam({"twin", "build", ply.string(), "--out", twin.string()}).exit_code, 2);  // --origin required
  EXPECT_FALSE(fs::exists(twin / "index.json"));
}

}  // namespace
}  // namespace twinslam::twin
