// OGC 3D Tiles: placement of the CesiumGS samples in W, golden placements, level choice, transform chains,
// external tilesets and malformed tilesets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <sstream>
#include <numbers>

#include "tiles_test_utils.hpp"
#include "twinslam/twin/tiles3d.hpp"

using namespace twinslam::twin;
using namespace tiles_test;

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;
// W's origin: the centre of the sample city (its tileset's region, radians), on the ellipsoid.
const GeoOrigin kOrigin{0.698874 * kDeg, -1.31968 * kDeg, 0.0};

std::string batched(const std::string& dir) { return sample("cesium-tools/Batched/" + dir + "/tileset.json"); }

LoadOptions options(double max_error = 0.0) {
  LoadOptions o;
  o.origin = kOrigin;
  o.max_geometric_error_m = max_error;
  return o;
}

// Per batch id: placed vertex bounds in W.
std::map<std::uint32_t, Eigen::AlignedBox3d> buildings(const TileContentRef& c, const EnuFrame& enu,
                                                       BatchTable* table) {
  std::vector<std::uint32_t> ids;
  const Mesh m = load_tile_content(c, enu, &ids, table);
  EXPECT_EQ(ids.size(), m.num_vertices());
  std::map<std::uint32_t, Eigen::AlignedBox3d> out;
  for (std::size_t i = 0; i < ids.size(); ++i) out[ids[i]].extend(m.p_W[i]);
  return out;
}

std::string tileset(const std::string& root) {
  return R"({"asset":{"version":"1.1"},"geometricError":100,"root":)" + root + "}";
}
std::string tile(double error, const std::string& uri, const std::string& more = "") {
  return R"({"boundingVolume":{"sphere":[0,0,0,1e7]},"geometricError":)" + std::to_string(error) +
         (uri.empty() ? "" : R"(,"content":{"uri":")" + uri + "\"}") + more + "}";
}

}  // namespace

TEST(Tiles3d, CityBuildingsLandWhereTheirBatchTablesSay) {
  // In the city tiles each building's batch-table Longitude / Latitude (radians) is the centre of its footprint and
  // its base lies on the ellipsoid (h = 0); Height is the building's height: the roof is Height metres above that
  // point. (Measured: footprint centre within 0.4 m of the position, base at 0.00 m, roof at Height +- 0.01 m.)
  LoadReport report;
  const std::string city = sample("cesium-samples/TilesetWithRequestVolume/city/tileset.json");
  const auto contents = select_3dtiles_contents(city, 0, &report);
  ASSERT_EQ(contents.size(), 4u);
  EXPECT_TRUE(report.rejected.empty());
  const EnuFrame enu(kOrigin);
  int checked = 0;
  for (const TileContentRef& c : contents) {
    BatchTable table;
    const auto placed = buildings(c, enu, &table);
    const auto* lon = table.find("Longitude");
    const auto* lat = table.find("Latitude");
    const auto* height = table.find("Height");
    ASSERT_TRUE(lon && lat && height) << c.path;
    ASSERT_EQ(placed.size(), table.batch_length) << c.path;
    for (const auto& [id, box] : placed) {
      const Eigen::Vector3d p_W = enu.from_lla((*lat)[id] * kDeg, (*lon)[id] * kDeg, 0.0);
      const Eigen::Vector2d centre = box.center().head<2>();
      EXPECT_LT((centre - p_W.head<2>()).norm(), 1.0) << c.path << " building " << id;
      EXPECT_NEAR(box.min().z(), p_W.z(), 1.0) << c.path << " building " << id;
      EXPECT_NEAR(box.max().z(), p_W.z() + (*height)[id], 1.0) << c.path << " building " << id;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 40);
}

TEST(Tiles3d, EveryValidSampleLoads) {
  for (const char* dir : {"BatchedWGS84", "BatchedWithRtcCenter", "BatchedWithTransformBox",
                          "BatchedWithTransformRegion", "BatchedDeprecated1"}) {
    LoadReport report;
    const Mesh m = load_3dtiles(batched(dir), options(), &report);
    EXPECT_EQ(report.parts_loaded, 1u) << dir;
    EXPECT_TRUE(report.rejected.empty()) << dir << ": " << (report.rejected.empty() ? "" : report.rejected[0]);
    EXPECT_EQ(m.num_triangles(), 120u) << dir;  // ten boxes of 12 triangles
    // The tileset's region: the buildings stand within ~100 m of the origin, between 0 and 20 m up.
    EXPECT_LT(m.bounds().center().head<2>().norm(), 100.0) << dir;
    EXPECT_GT(m.bounds().min().z(), -1.0) << dir;
    EXPECT_LT(m.bounds().max().z(), 20.0) << dir;
  }
  // The root sample: the external city tileset (4 b3dm), building.b3dm under its tile transform; points.pnts is
  // point-cloud content, which this loader does not read: it is reported, not silently dropped.
  LoadReport report;
  const Mesh all = load_3dtiles(sample("cesium-samples/TilesetWithRequestVolume/tileset.json"), options(), &report);
  EXPECT_EQ(report.parts_loaded, 5u);
  ASSERT_EQ(report.rejected.size(), 1u);
  EXPECT_NE(report.rejected[0].find("points.pnts"), std::string::npos) << report.rejected[0];
  EXPECT_NE(report.rejected[0].find("not supported"), std::string::npos) << report.rejected[0];
  // building.b3dm: its transform scales the 13.42 m model by 5 and stands it on the ellipsoid; the root region's
  // maximum height, 67.01 m, is its roof.
  const std::string root = sample("cesium-samples/TilesetWithRequestVolume/tileset.json");
  const auto contents = select_3dtiles_contents(root, 0, nullptr);
  ASSERT_EQ(contents.size(), 6u);  // 4 city tiles, building, points (rejected only when read)
  const EnuFrame enu(kOrigin);
  for (const TileContentRef& c : contents) {
    if (c.path.find("building.b3dm") == std::string::npos) continue;
    const Eigen::AlignedBox3d b = load_tile_content(c, enu).bounds();
    EXPECT_NEAR(b.min().z(), 0.0, 1.0);
    EXPECT_NEAR(b.max().z(), 67.01, 1.0);
    EXPECT_NEAR(b.sizes().x(), 2 * 1.869 * 5, 2.0);  // the tile's box half-axis 1.869 m, times the scale 5
  }
  EXPECT_NEAR(all.bounds().max().z(), 67.01, 1.0);
}

TEST(Tiles3d, TransformedTilesLandOnTheirGoldenPlacement) {
  // BatchedWGS84 holds the ten buildings' vertices in ECEF directly (no transform, no RTC): the golden placement.
  // BatchedWithTransformBox / -Region and the legacy BatchedDeprecated1 hold the same vertices (same order) in a
  // local ENU frame under a tile transform. The golden file stores ECEF as float32, so its vertices are off by up
  // to half a float32 step per axis: 0.0625 m at |x| ~ 1.2e6 m, 0.25 m at |y|, |z| ~ 4e6 m -> 0.36 m in all.
  const Mesh golden = load_3dtiles(batched("BatchedWGS84"), options(), nullptr);
  ASSERT_EQ(golden.num_vertices(), 240u);
  const double kFloat32Bound = std::sqrt(0.0625 * 0.0625 + 2 * 0.25 * 0.25);
  for (const char* dir : {"BatchedWithTransformBox", "BatchedWithTransformRegion", "BatchedDeprecated1"}) {
    const Mesh placed = load_3dtiles(batched(dir), options(), nullptr);
    ASSERT_EQ(placed.num_vertices(), golden.num_vertices()) << dir;
    double worst = 0.0;
    for (std::size_t i = 0; i < golden.num_vertices(); ++i) {
      worst = std::max(worst, (placed.p_W[i] - golden.p_W[i]).norm());
    }
    EXPECT_LT(worst, kFloat32Bound + 1e-3) << dir;
  }
  // BatchedWithRtcCenter: the TransformBox vertices plus RTC_CENTER (0.1, 0.2, 0.3). The spec adds RTC_CENTER in
  // the z-up tile frame, after the y-up -> z-up turn and before the tile transform: every vertex moves by
  // R_W_ECEF * R_tile * rtc. (Added after the transform it would be R_W_ECEF * rtc; added in the y-up frame,
  // R_W_ECEF * R_tile * (0.1, 0.3, -0.2): both differ by more than 0.1 m.)
  const Mesh box = load_3dtiles(batched("BatchedWithTransformBox"), options(), nullptr);
  const Mesh rtc = load_3dtiles(batched("BatchedWithRtcCenter"), options(), nullptr);
  ASSERT_EQ(rtc.num_vertices(), box.num_vertices());
  const auto contents = select_3dtiles_contents(batched("BatchedWithRtcCenter"), 0, nullptr);
  ASSERT_EQ(contents.size(), 1u);
  const EnuFrame enu(kOrigin);
  const Eigen::Matrix3d R_ECEF_tile = contents[0].T_ECEF_tile.topLeftCorner<3, 3>();
  const Eigen::Vector3d shift_W = enu.R_W_ECEF() * R_ECEF_tile * Eigen::Vector3d(0.1, 0.2, 0.3);
  for (std::size_t i = 0; i < box.num_vertices(); ++i) {
    ASSERT_LT((rtc.p_W[i] - box.p_W[i] - shift_W).norm(), 1e-3) << i;
  }
}

TEST(Tiles3d, LevelChoiceFollowsGeometricErrorAndRefine) {
  Scratch tmp("levels");
  const std::string city = sample("cesium-samples/TilesetWithRequestVolume/city/");
  auto write = [&](const std::string& refine) {
    const std::string children = R"(,"refine":")" + refine + R"(","children":[)" + tile(0, city + "lr.b3dm") + "," +
                                 tile(0, city + "ur.b3dm") + "]";
    write_text(tmp.path(refine + ".json"), tileset(tile(50, city + "ll.b3dm", children)));
    return tmp.path(refine + ".json");
  };
  auto names = [](const std::vector<TileContentRef>& v) {
    std::string s;
    for (const auto& c : v) s += std::filesystem::path(c.path).filename().string() + " ";
    return s;
  };
  const std::string replace = write("REPLACE");
  const std::string add = write("ADD");
  EXPECT_EQ(names(select_3dtiles_contents(replace, 0, nullptr)), "lr.b3dm ur.b3dm ");         // leaves replace the root
  EXPECT_EQ(names(select_3dtiles_contents(add, 0, nullptr)), "ll.b3dm lr.b3dm ur.b3dm ");     // leaves add to it
  EXPECT_EQ(names(select_3dtiles_contents(replace, 50, nullptr)), "ll.b3dm ");               // root is good enough
  EXPECT_EQ(names(select_3dtiles_contents(add, 80, nullptr)), "ll.b3dm ");
  EXPECT_EQ(names(select_3dtiles_contents(replace, 49.9, nullptr)), "lr.b3dm ur.b3dm ");
}

TEST(Tiles3d, TransformsChainParentTimesChild) {
  // Parent: a 100 m ECEF translation d; child: the BatchedWithTransformBox transform T. parent * child puts every
  // vertex at golden + d; child * parent would put it at golden + R(T) d, ~25 m away from that.
  Scratch tmp("chain");
  const std::string dir = sample("cesium-tools/Batched/BatchedWithTransformBox/");
  const std::string T = R"([0.9686356343768792,0.24848542777253735,0,0,-0.15986460744966327,0.623177611820219,)"
                        R"(0.765567091384559,0,0.19023226619126932,-0.7415555652213445,0.6433560667227647,0,)"
                        R"(1215011.9317263428,-4736309.3434217675,4081602.0044800863,1])";
  const std::string child = tile(0, dir + "batchedWithTransformBox.b3dm", R"(,"transform":)" + T);
  const std::string parent = R"(,"refine":"ADD","transform":[1,0,0,0,0,1,0,0,0,0,1,0,100,0,0,1],"children":[)";
  write_text(tmp.path("chain.json"), tileset(tile(10, "", parent + child + "]")));
  const Mesh chained = load_3dtiles(tmp.path("chain.json"), options(), nullptr);
  const Mesh golden = load_3dtiles(dir + "tileset.json", options(), nullptr);
  ASSERT_EQ(chained.num_vertices(), golden.num_vertices());
  const EnuFrame enu(kOrigin);
  const Eigen::Vector3d d_W = enu.R_W_ECEF() * Eigen::Vector3d(100, 0, 0);
  for (std::size_t i = 0; i < golden.num_vertices(); ++i) {
    ASSERT_LT((chained.p_W[i] - golden.p_W[i] - d_W).norm(), 1e-3) << i;
  }
}

TEST(Tiles3d, BadContentIsRejectedAndLoadingContinues) {
  Scratch tmp("reject");
  const std::string city = sample("cesium-samples/TilesetWithRequestVolume/city/");
  const std::vector<std::uint8_t> ll = bytes_of(city + "ll.b3dm");
  write_bytes(tmp.path("cut.b3dm"), {ll.begin(), ll.begin() + 500});
  write_bytes(tmp.path("invalid.b3dm"), bytes_of(sample("cesium-validator/invalid.b3dm")));
  write_text(tmp.path("self.json"), tileset(tile(0, "self.json")));
  const std::string children = R"(,"refine":"ADD","children":[)" + tile(0, "cut.b3dm") + "," +
                               tile(0, "missing.b3dm") + "," + tile(0, "invalid.b3dm") + "," +
                               tile(0, city + "lr.b3dm") + "," + tile(0, "self.json") + "]";
  write_text(tmp.path("tileset.json"), tileset(tile(10, "", children)));
  LoadReport report;
  const Mesh m = load_3dtiles(tmp.path("tileset.json"), options(), &report);
  EXPECT_EQ(report.parts_loaded, 1u);
  EXPECT_GT(m.num_triangles(), 0u);
  ASSERT_EQ(report.rejected.size(), 4u);
  std::string all;
  for (const auto& r : report.rejected) all += r + "\n";
  EXPECT_NE(all.find("cut.b3dm: b3dm byteLength 9700 exceeds the 500 bytes available"), std::string::npos) << all;
  EXPECT_NE(all.find("missing.b3dm: cannot open"), std::string::npos) << all;
  EXPECT_NE(all.find("invalid.b3dm: b3dm version 2 unsupported"), std::string::npos) << all;
  EXPECT_NE(all.find("self.json refers back to itself (cycle)"), std::string::npos) << all;
}

TEST(Tiles3d, MalformedTilesetThrowsWithTheReason) {
  Scratch tmp("malformed");
  auto expect = [&](const std::string& text, const std::string& reason) {
    write_text(tmp.path("t.json"), text);
    expect_input_error([&] { load_3dtiles(tmp.path("t.json"), options(), nullptr); }, {"t.json", reason});
  };
  expect(R"({"asset":{"version":"1.0"},"root":{)", "malformed");
  expect(R"({"root":{}})", "lacks asset");
  expect(R"({"asset":{"version":1},"root":{}})", "asset.version is not a string");
  expect(R"({"asset":{"version":"7.0"},"root":{}})", "'7.0' unsupported");
  expect(R"({"asset":{"version":"1.0"}})", "root");
  expect(R"({"asset":{"version":"1.0"},"root":{"boundingVolume":{"sphere":[0,0,0,1]}}})", "geometricError missing");
  expect(tileset(R"({"geometricError":-1,"boundingVolume":{"sphere":[0,0,0,1]}})"), "geometricError is not a number");
  expect(tileset(R"({"geometricError":1})"), "boundingVolume missing");
  expect(tileset(R"({"geometricError":1,"boundingVolume":{"region":[0,0,7,1,0,1]}})"), "region longitude");
  expect(tileset(R"({"geometricError":1,"boundingVolume":{"box":[0,0,0]}})"), "box is not 12");
  expect(tileset(tile(1, "", R"(,"transform":[1,0,0,0])")), "transform is not 16");
  expect(tileset(tile(1, "", R"(,"refine":"MERGE")")), "refine 'MERGE'");
  expect(tileset(tile(1, "", R"(,"children":[{"geometricError":0}])")), "root/0: boundingVolume missing");
  expect_input_error([] { load_3dtiles("/nonexistent/tileset.json", options(), nullptr); },
                     {"/nonexistent/tileset.json", "cannot open"});
}

TEST(Tiles3d, CorruptedTilesetTextNeverCrashes) {
  // Characters of the sample root tileset replaced at random (it references the real city / building files by
  // absolute path): each load returns a mesh or throws InputError naming the tileset, nothing else.
  Scratch tmp("fuzz");
  std::ifstream in(sample("cesium-samples/TilesetWithRequestVolume/tileset.json"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string dir = sample("cesium-samples/TilesetWithRequestVolume/");
  for (const char* uri : {"city/tileset.json", "building.b3dm", "points.pnts"}) {
    const std::size_t at = text.find(uri);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::strlen(uri), dir + uri);
  }
  const char* tokens[] = {"-1", "0", "1e400", "\"x\"", "[", "]", "{", "}", ",", "null", "[1,2]", "{}", "true"};
  std::mt19937 rng(5);
  int errors = 0;
  for (int trial = 0; trial < 150; ++trial) {
    std::string t = text;
    for (int k = 0; k < 2; ++k) t.replace(rng() % t.size(), 1 + rng() % 3, tokens[rng() % std::size(tokens)]);
    write_text(tmp.path("t.json"), t);
    try {
      LoadReport report;
      load_3dtiles(tmp.path("t.json"), options(), &report);
    } catch (const twinslam::InputError& e) {
      ++errors;
      ASSERT_NE(std::string(e.what()).find("t.json"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(errors, 50);
}

TEST(Tiles3d, GltfContentIsTurnedZUpAndPlacedWithCesiumRtc) {
  // A 1.1 tileset with two glTF contents of one triangle (0,0,0) (1,0,0) (0,1,0) (y-up model frame, buffer in an
  // external .bin next to the content), under a tile transform that maps the tile frame onto W's axes at W's
  // origin. y-up -> z-up turns model +y into up; the second content's CESIUM_RTC center (10, 20, 30), given z-up,
  // moves it by exactly that in W.
  Scratch tmp("gltf_content");
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::vector<std::uint8_t> bin(sizeof(xyz));
  std::memcpy(bin.data(), xyz, sizeof(xyz));
  write_bytes(tmp.path("tri.bin"), bin);
  auto gltf = [](const std::string& extra) {
    return R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
           R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"tri.bin"}])" + extra +
           "}";
  };
  write_text(tmp.path("plain.gltf"), gltf(""));
  const std::string rtc = R"(,"extensionsUsed":["CESIUM_RTC"],"extensions":{"CESIUM_RTC":{"center":[10,20,30]}})";
  write_text(tmp.path("rtc.gltf"), gltf(rtc));
  const EnuFrame enu(kOrigin);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();  // tile frame = W axes, at W's origin, in ECEF
  T.topLeftCorner<3, 3>() = enu.R_W_ECEF().transpose();
  T.topRightCorner<3, 1>() = enu.to_ecef(Eigen::Vector3d::Zero());
  std::ostringstream transform;
  transform.precision(17);
  for (int i = 0; i < 16; ++i) transform << (i ? "," : "[") << T(i % 4, i / 4);
  transform << "]";
  const std::string children = R"(,"refine":"ADD","transform":)" + transform.str() + R"(,"children":[)" +
                               tile(0, "plain.gltf") + "," + tile(0, "rtc.gltf") + "]";
  write_text(tmp.path("tileset.json"), tileset(tile(1, "", children)));
  LoadReport report;
  const Mesh m = load_3dtiles(tmp.path("tileset.json"), options(), &report);
  EXPECT_EQ(report.parts_loaded, 2u);
  ASSERT_EQ(report.warnings.size(), 1u);  // CESIUM_RTC is deprecated: accepted as CesiumJS does, with a warning
  EXPECT_NE(report.warnings[0].find("rtc.gltf: glTF CESIUM_RTC extension (deprecated)"), std::string::npos);
  ASSERT_EQ(m.num_vertices(), 6u);
  const Eigen::Vector3d expected[3] = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT((m.p_W[i] - expected[i]).norm(), 1e-6) << i;
    EXPECT_LT((m.p_W[i + 3] - expected[i] - Eigen::Vector3d(10, 20, 30)).norm(), 1e-6) << i;
  }
}

TEST(Tiles3d, CompositeTilesLoadTheirB3dmAndReportThePointCloud) {
  // A cmpt of ll.b3dm, lr.b3dm and points.pnts (each padded to 8 bytes, its byteLength patched to the padded size)
  // gives the same mesh as ll + lr loaded as separate tiles; the point cloud is listed as skipped.
  Scratch tmp("cmpt");
  const std::string dir = sample("cesium-samples/TilesetWithRequestVolume/");
  std::vector<std::uint8_t> cmpt = {'c', 'm', 'p', 't', 1, 0, 0, 0, 0, 0, 0, 0, 3, 0, 0, 0};  // version 1, 3 tiles
  for (const char* f : {"city/ll.b3dm", "city/lr.b3dm", "points.pnts"}) {
    std::vector<std::uint8_t> inner = bytes_of(dir + f);
    inner.resize((inner.size() + 7) / 8 * 8, 0);
    put_u32(inner, 8, static_cast<std::uint32_t>(inner.size()));
    cmpt.insert(cmpt.end(), inner.begin(), inner.end());
  }
  put_u32(cmpt, 8, static_cast<std::uint32_t>(cmpt.size()));
  write_bytes(tmp.path("city.cmpt"), cmpt);
  std::vector<std::uint8_t> broken = cmpt;
  put_u32(broken, 12, 1u << 30);
  write_bytes(tmp.path("broken.cmpt"), broken);
  write_text(tmp.path("cmpt.json"), tileset(tile(0, "city.cmpt")));
  const std::string two = R"(,"refine":"ADD","children":[)" + tile(0, dir + "city/ll.b3dm") + "," +
                          tile(0, dir + "city/lr.b3dm") + "]";
  write_text(tmp.path("separate.json"), tileset(tile(1, "", two)));
  write_text(tmp.path("broken.json"), tileset(tile(0, "broken.cmpt")));
  LoadReport report;
  const Mesh composite = load_3dtiles(tmp.path("cmpt.json"), options(), &report);
  const Mesh separate = load_3dtiles(tmp.path("separate.json"), options(), nullptr);
  EXPECT_EQ(report.parts_loaded, 1u);
  ASSERT_EQ(report.rejected.size(), 1u);
  EXPECT_NE(report.rejected[0].find("city.cmpt [inner tile 2]: pnts content not supported"), std::string::npos)
      << report.rejected[0];
  ASSERT_EQ(composite.num_vertices(), separate.num_vertices());
  EXPECT_EQ(composite.triangles, separate.triangles);
  for (std::size_t i = 0; i < composite.num_vertices(); ++i) {
    ASSERT_LT((composite.p_W[i] - separate.p_W[i]).norm(), 1e-9);
  }
  LoadReport bad;
  EXPECT_TRUE(load_3dtiles(tmp.path("broken.json"), options(), &bad).empty());
  ASSERT_EQ(bad.rejected.size(), 1u);
  EXPECT_NE(bad.rejected[0].find("broken.cmpt: cmpt tilesLength 1073741824 is implausible"), std::string::npos)
      << bad.rejected[0];
}
