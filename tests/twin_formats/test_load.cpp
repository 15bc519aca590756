// load_twin_source: format by extension / content, OBJ, --crs for meshes, the glTF and 3D Tiles branches, errors.
#include <gtest/gtest.h>

#include "twin_test_utils.hpp"
#include "twinslam/twin/gltf.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/obj.hpp"

using namespace twinslam::twin;
using twin_test::expect_input_error;
using twin_test::Scratch;
using twin_test::write_text;

namespace {
const std::string kData = std::string(TWINSLAM_SHARED_DIR) + "/data";
}

TEST(Load, ObjFaceFormsNegativeIndicesAndPolygons) {
  Scratch tmp;
  const std::string path = write_text(tmp / "house.obj",
                                      "# a unit square and a pentagon\nmtllib none.mtl\no thing\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                                      "f 1 2 3\nf 1/1 3/1 4/1\n"
                                      "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0.5 1.5 1\nv 0 1 1\n"
                                      "g roof\nusemtl red\nf -5//1 -4//1 -3//1 -2//1 -1//1\nf 1/1/1 2/1/1 6/1/1\n");
  const Mesh m = load_twin_source(path, LoadOptions{});
  ASSERT_EQ(m.num_vertices(), 9u);
  ASSERT_EQ(m.num_triangles(), 2u + 3u + 1u);
  EXPECT_EQ(m.triangles[2], Eigen::Vector3i(4, 5, 6));  // -5 = the 5th vertex from the end = index 4
  EXPECT_EQ(m.triangles[4], Eigen::Vector3i(4, 7, 8));
  EXPECT_NEAR(m.total_area(), 1.0 + 1.25 + 0.5, 1e-12);  // square, pentagon, wall triangle (0,0,0)(1,0,0)(1,0,1)
}

TEST(Load, ObjErrorsNameFileAndLine) {
  Scratch tmp;
  const std::string range = write_text(tmp / "range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n");
  expect_input_error([&] { read_obj(range); }, range + ":4", "face index 4 out of range");
  const std::string zero = write_text(tmp / "zero.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n");
  expect_input_error([&] { read_obj(zero); }, zero + ":4", "out of range");
  const std::string nan = write_text(tmp / "nan.obj", "v 0 nan 0\n");
  expect_input_error([&] { read_obj(nan); }, nan + ":1", "not a finite number");
  const std::string shortv = write_text(tmp / "short.obj", "v 0 1\n");
  expect_input_error([&] { read_obj(shortv); }, shortv + ":1", "vertex needs x y z");
  const std::string word = write_text(tmp / "word.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 x\n");
  expect_input_error([&] { read_obj(word); }, word + ":4", "bad face corner 'x'");
  const std::string two = write_text(tmp / "two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expect_input_error([&] { read_obj(two); }, two + ":3", "at least 3 vertices");
}

TEST(Load, MeshInAProjectedCrsLandsInW) {
  // An OBJ in Swiss LV95 with --crs EPSG:2056: the vertex at W's origin goes to (0, 0, 0), one 100 m north to ~+100 m.
  Scratch tmp;
  const std::string path =
      write_text(tmp / "lv95.obj", "v 2600000 1200000 500\nv 2600000 1200100 500\nv 2600100 1200000 510\nf 1 2 3\n");
  LoadOptions options;
  options.crs = "EPSG:2056";
  const Eigen::Vector3d o = CrsTransform("EPSG:2056").to_lla({2600000, 1200000, 500});
  options.origin = {o.x(), o.y(), o.z()};
  const Mesh m = load_twin_source(path, options);
  EXPECT_LT(m.p_W[0].norm(), 1e-6);
  EXPECT_NEAR(m.p_W[1].norm(), 100.0, 0.05);  // LV95's scale error near Bern is ~1e-5; the ellipsoid drops 0.8 mm
  EXPECT_GT(m.p_W[1].y(), 99.9);
  EXPECT_NEAR(m.p_W[2].z(), 10.0, 0.01);
}

TEST(Load, JsonByContentGltfAndTilesets) {
  LoadOptions options;
  options.origin = {52.0, 4.36, 43.0};
  LoadReport report;
  const Mesh delft = load_twin_source(kData + "/cityjson/delft.json", options, &report);  // .json: CityJSON by content
  EXPECT_EQ(report.parts_loaded, 570u);
  EXPECT_GT(delft.num_triangles(), 10000u);

  // A standalone glTF is turned from y-up to z-up.
  const std::string box = kData + "/3dtiles/cesium-tools/BoxDraco.glb";
  const Mesh y_up = load_gltf_file(box);
  const Mesh z_up = load_twin_source(box, options);
  ASSERT_EQ(z_up.num_triangles(), 12u);
  ASSERT_EQ(z_up.num_vertices(), y_up.num_vertices());
  for (std::size_t i = 0; i < y_up.num_vertices(); ++i)
    EXPECT_EQ(z_up.p_W[i], Eigen::Vector3d(y_up.p_W[i].x(), -y_up.p_W[i].z(), y_up.p_W[i].y()));

  // A 3D Tiles tileset.json goes to the tileset loader (which places content from ECEF into W).
  LoadReport tiles_report;
  const Mesh tiles =
      load_twin_source(kData + "/3dtiles/cesium-samples/TilesetWithRequestVolume/tileset.json", options, &tiles_report);
  EXPECT_GT(tiles.num_triangles(), 0u);
  EXPECT_GT(tiles_report.parts_loaded, 0u);
}

TEST(Load, UnknownOrMissingSourcesAreInputErrors) {
  Scratch tmp;
  const LoadOptions options;
  const std::string geojson = write_text(tmp / "shapes.json", R"({"type": "FeatureCollection", "features": []})");
  expect_input_error([&] { load_twin_source(geojson, options); }, geojson, "neither CityJSON");
  const std::string xyz = write_text(tmp / "cloud.xyz", "1 2 3\n");
  expect_input_error([&] { load_twin_source(xyz, options); }, xyz, "unknown twin source format");
  const std::string missing = (tmp / "missing.ply").string();
  expect_input_error([&] { load_twin_source(missing, options); }, missing, "no such file");
}
