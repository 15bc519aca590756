// Building a twin store, index.json write/read and its validation, loading tiles (store.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_meshes.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::twin {
namespace {

namespace fs = std::filesystem;

class TwinStore : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twin_store_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    city_ = test::box_city(-60.0, -35.0, 9, 15.0, 15, 2);
  }
  void TearDown() override { fs::remove_all(dir_); }

  nlohmann::json index_json() const {
    std::ifstream in(dir_ / "index.json");
    return nlohmann::json::parse(in);
  }
  void write_index(const nlohmann::json& j) const { std::ofstream(dir_ / "index.json") << j.dump(); }
  // read_twin_index must fail with a message naming index.json and `key`.
  void expect_index_error(const std::string& key) const {
    try {
      read_twin_index(dir_.string());
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("index.json"), std::string::npos) << what;
      EXPECT_NE(what.find(key), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }

  fs::path dir_;
  Mesh city_;
  const GeoOrigin origin_{47.3769, 8.5417, 408.0};
};

TEST_F(TwinStore, BuildWritesAnIndexThatReadsBackAndTilesThatDecodeToTheMesh) {
  const StoreConfig config;
  const TwinIndex built = build_twin_store(city_, origin_, config, dir_.string());
  const TwinIndex read = read_twin_index(dir_.string());
  EXPECT_EQ(read.twin_id, built.twin_id);
  EXPECT_EQ(read.twin_id.size(), 16u);
  EXPECT_DOUBLE_EQ(read.origin.lat_deg, 47.3769);
  EXPECT_DOUBLE_EQ(read.origin.alt_m, 408.0);
  EXPECT_TRUE(read.extent_W.isApprox(city_.bounds()));  // extent of the source itself
  EXPECT_EQ(read.extent_W.min(), city_.bounds().min());
  ASSERT_EQ(read.tiles.size(), built.tiles.size());
  EXPECT_EQ(read.triangles, built.triangles);
  EXPECT_GE(read.triangles, city_.num_triangles());
  double area = 0;
  std::size_t points = 0;
  for (const TileInfo& info : read.tiles) {
    EXPECT_TRUE(fs::exists(dir_ / "tiles" / (info.key.str() + ".mesh.drc")));
    const Tile tile = load_tile(dir_.string(), read, info.key);
    EXPECT_EQ(tile.mesh_W.num_triangles(), info.triangles);
    EXPECT_EQ(tile.points_W.p_W.size(), info.points);
    EXPECT_EQ(read_tile_file(dir_.string(), info.key, true).size(), info.points_bytes);
    for (const Eigen::Vector3d& p : tile.mesh_W.p_W) {
      EXPECT_TRUE(info.bounds_W.exteriorDistance(p) < 1e-3) << info.key.str();
    }
    area += tile.mesh_W.total_area();
    points += tile.points_W.p_W.size();
  }
  EXPECT_NEAR(area, city_.total_area(), 1e-5 * city_.total_area());
  const double expected = city_.total_area() / (config.point_spacing_m * config.point_spacing_m);
  EXPECT_NEAR(static_cast<double>(points), expected, 0.02 * expected);
  EXPECT_EQ(points, read.points);
  EXPECT_THROW(load_tile(dir_.string(), read, TileKey{100, 100}), InputError);
}

TEST_F(TwinStore, SameInputSameIdOtherSeedOtherIdAndStaleTilesRemoved) {
  const TwinIndex a = build_twin_store(city_, origin_, StoreConfig{}, dir_.string());
  EXPECT_EQ(build_twin_store(city_, origin_, StoreConfig{}, dir_.string()).twin_id, a.twin_id);
  StoreConfig other;
  other.seed = 2;
  EXPECT_NE(build_twin_store(city_, origin_, other, dir_.string()).twin_id, a.twin_id);
  // A smaller twin into the same folder: the old tiles are gone, only the new ones remain.
  Mesh small;
  test::add_box(&small, {1, 1, 0}, {9, 9, 9});
  const TwinIndex b = build_twin_store(small, origin_, StoreConfig{}, dir_.string());
  ASSERT_EQ(b.tiles.size(), 1u);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "tiles")) files += entry.path().extension() == ".drc";
  EXPECT_EQ(files, 2u);
}

TEST_F(TwinStore, PointSetSourceIsStoredAsPointsOnly) {
  Mesh pts;
  for (int i = 0; i < 400; ++i) {
    pts.p_W.emplace_back(-30.0 + i * 0.25, 5.0 + 0.1 * i, 2.0);
    pts.n_W.emplace_back(0, 0, 1);
  }
  const TwinIndex index = build_twin_store(pts, origin_, StoreConfig{}, dir_.string());
  EXPECT_EQ(index.triangles, 0u);
  EXPECT_EQ(index.points, 400u);
  ASSERT_EQ(index.tiles.size(), 3u);  // e from -30 to 69.75: tiles -1, 0, 1
  EXPECT_FALSE(fs::exists(dir_ / "tiles" / "0_0.mesh.drc"));
  const TwinIndex read = read_twin_index(dir_.string());
  const Tile tile = load_tile(dir_.string(), read, TileKey{0, 0});
  EXPECT_TRUE(tile.mesh_W.empty());
  EXPECT_EQ(tile.points_W.p_W.size(), 200u);  // e in [0, 50): i = 120 .. 319
  EXPECT_NEAR(tile.points_W.n_W[0].z(), 1.0, 1e-6);
}

TEST_F(TwinStore, MissingOrCorruptTileFilesAreInputErrors) {
  const TwinIndex index = build_twin_store(city_, origin_, StoreConfig{}, dir_.string());
  const TileKey key = index.tiles.front().key;
  const fs::path mesh_file = dir_ / "tiles" / (key.str() + ".mesh.drc");
  std::ofstream(mesh_file, std::ios::binary | std::ios::trunc) << "DRACO garbage";
  EXPECT_THROW(load_tile(dir_.string(), index, key), InputError);
  fs::remove(mesh_file);
  try {
    load_tile(dir_.string(), index, key);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key.str() + ".mesh.drc"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_tile_file(dir_.string(), key, false), InputError);
  // A valid file of another tile in its place: counts disagree with the index.
  fs::copy_file(dir_ / "tiles" / (index.tiles.back().key.str() + ".mesh.drc"), mesh_file);
  if (index.tiles.back().triangles != index.tiles.front().triangles) {
    EXPECT_THROW(load_tile(dir_.string(), index, key), InputError);
  }
}

TEST_F(TwinStore, MalformedIndexIsAnInputErrorNamingTheKey) {
  build_twin_store(city_, origin_, StoreConfig{}, dir_.string());
  const nlohmann::json good = index_json();
  EXPECT_NO_THROW(read_twin_index(dir_.string()));
  auto edited = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = good;
    edit(j);
    write_index(j);
  };
  edited([](auto& j) { j.erase("tiles"); });
  expect_index_error("tiles");
  edited([](auto& j) { j["tile_size_m"] = "50"; });
  expect_index_error("tile_size_m");
  edited([](auto& j) { j["format_version"] = 2; });
  expect_index_error("format_version");
  edited([](auto& j) { j["origin"] = {47.0, 8.0}; });
  expect_index_error("origin");
  edited([](auto& j) { j["tiles"][0].erase("bounds_enu"); });
  expect_index_error("tiles[0].bounds_enu");
  edited([](auto& j) { j["tiles"][1]["triangles"] = -3; });
  expect_index_error("tiles[1].triangles");
  edited([](auto& j) { j["tiles"][0]["key"] = "9_9"; });
  expect_index_error("tiles[0].key");
  edited([](auto& j) { j["tiles"][0]["files"]["mesh"] = "../../etc/passwd"; });
  expect_index_error("tiles[0].files.mesh");
  edited([](auto& j) { j["totals"]["points"] = 1; });
  expect_index_error("totals.points");
  std::ofstream(dir_ / "index.json") << "{\"format\": \"twinslam-twin\", ";  // truncated
  expect_index_error("not valid JSON");
  fs::remove(dir_ / "index.json");
  expect_index_error("cannot read");
}

}  // namespace
}  // namespace twinslam::twin
