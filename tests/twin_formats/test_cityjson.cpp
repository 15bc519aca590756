// CityJSON: the Delft and Den Haag models from the cjio test data, the CRS handling and malformed files.
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "twin_test_utils.hpp"
#include "twinslam/twin/cityjson.hpp"

using namespace twinslam::twin;
using twin_test::expect_input_error;
using twin_test::Scratch;
using twin_test::write_text;

namespace {

const std::string kDelft = std::string(TWINSLAM_SHARED_DIR) + "/data/cityjson/delft.json";
const std::string kDenHaag = std::string(TWINSLAM_SHARED_DIR) + "/data/cityjson/denhaag-lod2-solids.city.json";

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The origin of W at the centre of a CityJSON file's geographicalExtent, on its lowest point.
GeoOrigin origin_at_extent_centre(const nlohmann::json& doc, const CrsTransform& crs) {
  const auto& e = doc["metadata"]["geographicalExtent"];
  const Eigen::Vector3d lla = crs.to_lla({(e[0].get<double>() + e[3].get<double>()) / 2,
                                          (e[1].get<double>() + e[4].get<double>()) / 2, e[2].get<double>()});
  return {lla.x(), lla.y(), lla.z()};
}

Eigen::AlignedBox3d object_bounds(const CityJsonModel& m, const CityObjectInfo& o) {
  Eigen::AlignedBox3d box;
  for (std::size_t t = o.first_triangle; t < o.first_triangle + o.num_triangles; ++t)
    for (int k = 0; k < 3; ++k) box.extend(m.mesh_W.p_W[m.mesh_W.triangles[t][k]]);
  return box;
}

}  // namespace

TEST(CityJson, DelftLoadsAllItsBuildingsInsideThePROJConvertedExtent) {
  const nlohmann::json doc = read_json(kDelft);
  std::size_t buildings_in_file = 0;
  for (const auto& [id, o] : doc["CityObjects"].items()) buildings_in_file += o["type"] == "Building";
  ASSERT_EQ(buildings_in_file, 160u);  // what the file holds (plus 410 roads, land use, plants, water, bridges...)

  const CrsTransform crs("EPSG:7415");
  LoadOptions options;
  options.origin = origin_at_extent_centre(doc, crs);
  LoadReport report;
  const CityJsonModel model = load_cityjson(kDelft, options, &report);  // CRS from metadata.referenceSystem (URL form)
  EXPECT_TRUE(report.rejected.empty()) << report.rejected.front();
  EXPECT_EQ(report.parts_loaded, doc["CityObjects"].size());  // 570: every object of Delft has geometry
  std::map<std::string, std::size_t> by_type;
  for (const CityObjectInfo& o : model.objects) {
    ++by_type[o.type];
    EXPECT_GT(o.num_triangles, 0u) << o.id;
  }
  EXPECT_EQ(by_type["Building"], 160u);
  // Every building's triangles cover its surfaces exactly: their area equals the surfaces' vector areas (Newell, in
  // the file's RD coordinates: outer ring minus holes), within 0.1 % (RD's scale factor near Delft is 1 +- 1e-4;
  // LoD1 surfaces are planar). (Delft's shells are not closed by vertex index, so closure cannot be checked here.)
  const auto& verts = doc["vertices"];
  const auto& tr = doc["transform"];
  auto rd = [&](int i) {
    return Eigen::Vector3d(verts[i][0].get<double>() * tr["scale"][0].get<double>(),
                           verts[i][1].get<double>() * tr["scale"][1].get<double>(),
                           verts[i][2].get<double>() * tr["scale"][2].get<double>());  // translate cancels in Newell
  };
  auto ring_area = [&](const nlohmann::json& ring) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < ring.size(); ++i) n += rd(ring[i]).cross(rd(ring[(i + 1) % ring.size()]));
    return n.norm() / 2.0;
  };
  std::size_t checked = 0;
  for (const CityObjectInfo& o : model.objects) {
    if (o.type != "Building") continue;
    double expected = 0.0;
    for (const auto& g : doc["CityObjects"][o.id]["geometry"])
      for (const auto& shell : g["boundaries"])
        for (const auto& surface : shell)
          for (std::size_t r = 0; r < surface.size(); ++r) expected += (r == 0 ? 1.0 : -1.0) * ring_area(surface[r]);
    double area = 0.0;
    for (std::size_t t = o.first_triangle; t < o.first_triangle + o.num_triangles; ++t)
      area += model.mesh_W.triangle_area(t);
    EXPECT_NEAR(area, expected, 1e-3 * expected) << o.id;
    ++checked;
  }
  EXPECT_EQ(checked, 160u);

  // metadata.geographicalExtent is the min / max of the RD coordinates: its four corners, converted independently,
  // bound a quadrilateral in W (RD's grid north turns ~0.8 deg from true north at Delft). Every vertex lies inside
  // and the outermost vertices touch each side, within 5 cm (the file's 1 mm quantization plus PROJ's rounding).
  const auto& e = doc["metadata"]["geographicalExtent"];
  const EnuFrame frame(options.origin);
  std::vector<Eigen::Vector2d> corner_W;
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{0, 1}, {3, 1}, {3, 4}, {0, 4}}) {
    const Eigen::Vector3d lla = crs.to_lla({e[x].get<double>(), e[y].get<double>(), 0.0});
    corner_W.push_back(frame.from_lla(lla.x(), lla.y(), lla.z()).head<2>());
  }
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d a = corner_W[side], b = corner_W[(side + 1) % 4];
    const Eigen::Vector2d inward = Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();  // corners run CCW
    double closest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : model.mesh_W.p_W) closest = std::min(closest, inward.dot(p.head<2>() - a));
    EXPECT_NEAR(closest, 0.0, 0.05) << "side " << side;
  }
  // Heights: NAP -0.452 .. 16.846 m through the same EGM96 geoid; W's up at the origin (the lowest point).
  const Eigen::AlignedBox3d box = model.mesh_W.bounds();
  EXPECT_NEAR(box.min().z(), 0.0, 0.05);
  EXPECT_NEAR(box.max().z(), 16.846 + 0.452, 0.05);
}

TEST(CityJson, DenHaagLod2SolidsAreClosedWithTheirRidgeHeights) {
  // The file has no metadata.referenceSystem: without --crs it is refused, with EPSG:7415 (RD New + NAP) it loads.
  LoadOptions options;
  options.origin = {52.08, 4.30, 45.0};
  expect_input_error([&] { load_cityjson(kDenHaag, options); }, kDenHaag, "no CRS");
  options.crs = "EPSG:7415";
  LoadReport report;
  const CityJsonModel model = load_cityjson(kDenHaag, options, &report);
  EXPECT_TRUE(report.rejected.empty());
  EXPECT_EQ(report.parts_loaded, 9u);  // 12 objects: 3 Buildings are parents without geometry, 9 parts are solids
  const nlohmann::json doc = read_json(kDenHaag);
  ASSERT_EQ(model.objects.size(), 9u);
  for (const CityObjectInfo& o : model.objects) {
    SCOPED_TRACE(o.id);
    EXPECT_EQ(o.lod, "2");
    EXPECT_GT(o.num_triangles, 0u);
    // Closed and consistently wound: every directed edge once, its reverse once; then the volume is positive.
    std::map<std::pair<int, int>, int> directed;
    double volume = 0.0;
    for (std::size_t t = o.first_triangle; t < o.first_triangle + o.num_triangles; ++t) {
      const Eigen::Vector3i& tri = model.mesh_W.triangles[t];
      for (int k = 0; k < 3; ++k) ++directed[{tri[k], tri[(k + 1) % 3]}];
      volume += model.mesh_W.p_W[tri[0]].dot(model.mesh_W.p_W[tri[1]].cross(model.mesh_W.p_W[tri[2]])) / 6.0;
    }
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
    }
    EXPECT_GT(volume, 0.1);  // m^3 (the smallest part, a dormer-like block, has ~0.5 m^3): outward-facing shells
    // Height of the solid = the file's own RelativeRidgeHeight attribute (ridge above ground), within 1 cm.
    const Eigen::AlignedBox3d box = object_bounds(model, o);
    EXPECT_NEAR(box.max().z() - box.min().z(), doc["CityObjects"][o.id]["attributes"]["RelativeRidgeHeight"].get<double>(),
                0.01);
    // Ground at NAP +3.5..6.2 m: ~43 m + NAP above the ellipsoid, so ~0..5 m above an origin at h = 45 m.
    EXPECT_GT(box.min().z(), -3.0);
    EXPECT_LT(box.min().z(), 8.0);
  }
}

TEST(CityJson, VersionsCrsFormsHolesAndRejectedObjects) {
  Scratch tmp;
  // CityJSON 1.0 without transform, URN CRS, a MultiSurface square with a hole at LoD 1 and 2 (only 2 is used),
  // a CompositeSurface, a bad object (index out of range) and a point geometry.
  const std::string path = write_text(tmp / "v10.json", R"({
    "type": "CityJSON", "version": "1.0",
    "metadata": {"referenceSystem": "urn:ogc:def:crs:EPSG::28992"},
    "CityObjects": {
      "a": {"type": "Building", "geometry": [
        {"type": "MultiSurface", "lod": 1, "boundaries": [[[0, 1, 2, 3]]]},
        {"type": "MultiSurface", "lod": 2, "boundaries": [[[0, 1, 2, 3], [4, 5, 6, 7]]]}]},
      "b": {"type": "Road", "geometry": [{"type": "CompositeSurface", "lod": 1, "boundaries": [[[0, 1, 2]]]}]},
      "c": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": 1, "boundaries": [[[0, 1, 99]]]}]},
      "d": {"type": "Building", "geometry": [{"type": "Solid", "lod": 1, "boundaries": [[0, 1, 2]]}]},
      "e": {"type": "TINRelief", "geometry": [{"type": "MultiPoint", "lod": 1, "boundaries": [0, 1]}]}
    },
    "vertices": [[155000, 463000, 0], [155010, 463000, 0], [155010, 463010, 0], [155000, 463010, 0],
                 [155004, 463004, 0], [155006, 463004, 0], [155006, 463006, 0], [155004, 463006, 0]]
  })");
  const CrsTransform rd("EPSG:28992");
  const Eigen::Vector3d o = rd.to_lla({155000, 463000, 0});
  LoadOptions options;
  options.origin = {o.x(), o.y(), o.z()};
  options.crs = "EPSG:2056";  // the file's own CRS wins
  LoadReport report;
  const CityJsonModel model = load_cityjson(path, options, &report);
  ASSERT_EQ(model.objects.size(), 2u);
  EXPECT_EQ(model.objects[0].lod, "2");
  double area_a = 0.0;
  for (std::size_t t = 0; t < model.objects[0].num_triangles; ++t) area_a += model.mesh_W.triangle_area(t);
  // 96 m^2 of RD grid; RD's scale factor at Amersfoort is 0.9999079, so 96.0177 m^2 on the ground.
  EXPECT_NEAR(area_a, 96.0 / (0.9999079 * 0.9999079), 0.001);
  EXPECT_GT(model.mesh_W.triangle_normal(0).z(), 0.99);
  double nearest = 1e9;  // RD (155000, 463000) is the origin of W
  for (const Eigen::Vector3d& p : model.mesh_W.p_W) nearest = std::min(nearest, p.norm());
  EXPECT_LT(nearest, 1e-6);
  EXPECT_EQ(report.parts_loaded, 2u);
  ASSERT_EQ(report.rejected.size(), 3u);
  EXPECT_NE(report.rejected[0].find("'c': MultiSurface: vertex index 99 out of range"), std::string::npos)
      << report.rejected[0];
  EXPECT_NE(report.rejected[1].find("'d': Solid: boundaries nesting"), std::string::npos) << report.rejected[1];
  EXPECT_NE(report.rejected[2].find("skipped MultiPoint"), std::string::npos) << report.rejected[2];
  for (const std::string& r : report.rejected) EXPECT_EQ(r.rfind(path, 0), 0u) << r;
}

TEST(CityJson, MalformedFilesAreInputErrors) {
  Scratch tmp;
  LoadOptions options;
  const std::string syntax = write_text(tmp / "syntax.city.json", R"({"type": "CityJSON", "version": "2.0",)");
  expect_input_error([&] { load_cityjson(syntax, options); }, syntax, "JSON syntax error");
  const std::string other = write_text(tmp / "other.city.json", R"({"type": "FeatureCollection"})");
  expect_input_error([&] { load_cityjson(other, options); }, other, "not a CityJSON file");
  const std::string version = write_text(tmp / "v3.city.json", R"({"type": "CityJSON", "version": "3.0"})");
  expect_input_error([&] { load_cityjson(version, options); }, version, "unsupported CityJSON version '3.0'");
  const std::string crs = write_text(tmp / "crs.city.json", R"({"type": "CityJSON", "version": "2.0",
      "transform": {"scale": [1, 1, 1], "translate": [0, 0, 0]}, "metadata": {"referenceSystem": "EPSG:999999"},
      "CityObjects": {}, "vertices": [[0, 0, 0]]})");
  expect_input_error([&] { load_cityjson(crs, options); }, crs, "unknown CRS 'EPSG:999999'");
  const std::string vertex = write_text(tmp / "vertex.city.json", R"({"type": "CityJSON", "version": "2.0",
      "transform": {"scale": [1, 1, 1], "translate": [0, 0, 0]}, "metadata": {"referenceSystem": "EPSG:28992"},
      "CityObjects": {}, "vertices": [[155000, 463000, "x"]]})");
  expect_input_error([&] { load_cityjson(vertex, options); }, vertex, "vertex 0 must be an array of 3 numbers");
  const std::string no_transform = write_text(tmp / "nt.city.json", R"({"type": "CityJSON", "version": "1.1",
      "CityObjects": {}, "vertices": []})");
  expect_input_error([&] { load_cityjson(no_transform, options); }, no_transform, "requires a transform");
}
