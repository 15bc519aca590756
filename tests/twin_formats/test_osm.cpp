// OSM XML buildings: heights from tags, footprints through EnuFrame, closed outward-facing blocks, multipolygons.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "twin_test_utils.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/osm.hpp"

using namespace twinslam::twin;
using twin_test::expect_input_error;
using twin_test::Scratch;
using twin_test::write_text;

namespace {

const GeoOrigin kOrigin{47.3769, 8.5417, 408.0};

struct OsmWriter {
  std::ostringstream xml;
  std::map<std::int64_t, std::pair<double, double>> nodes;  // id -> lat, lon
  std::int64_t next_node = 1;
  OsmWriter() { xml.precision(12); }
  // A node at roughly (east, north) metres from the origin.
  std::int64_t node(double e, double n) {
    const double lat = kOrigin.lat_deg + n / 111195.0;
    const double lon = kOrigin.lon_deg + e / (111195.0 * std::cos(kOrigin.lat_deg * M_PI / 180.0));
    nodes[next_node] = {std::round(lat * 1e7) / 1e7, std::round(lon * 1e7) / 1e7};  // OSM's 1e-7 deg grid
    return next_node++;
  }
  std::vector<std::int64_t> box(double e, double n, double w, double d) {
    return {node(e, n), node(e + w, n), node(e + w, n + d), node(e, n + d)};
  }
  void way(std::int64_t id, const std::vector<std::int64_t>& refs, bool close,
           const std::vector<std::pair<std::string, std::string>>& tags) {
    ways << "  <way id=\"" << id << "\" version=\"1\">\n";
    for (std::int64_t r : refs) ways << "    <nd ref=\"" << r << "\"/>\n";
    if (close) ways << "    <nd ref=\"" << refs.front() << "\"/>\n";
    for (const auto& [k, v] : tags) ways << "    <tag k=\"" << k << "\" v=\"" << v << "\"/>\n";
    ways << "  </way>\n";
  }
  std::ostringstream ways, relations;
  std::string str() {
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\" generator=\"test\">\n";
    for (const auto& [id, ll] : nodes)
      xml << "  <node id=\"" << id << "\" version=\"1\" lat=\"" << ll.first << "\" lon=\"" << ll.second << "\"/>\n";
    xml << ways.str() << relations.str() << "</osm>\n";
    return xml.str();
  }
};

}  // namespace

TEST(Osm, HeightTagsParse) {
  double m = 0.0;
  EXPECT_TRUE(parse_osm_height("12", &m));
  EXPECT_DOUBLE_EQ(m, 12.0);
  EXPECT_TRUE(parse_osm_height("12.5 m", &m));
  EXPECT_DOUBLE_EQ(m, 12.5);
  EXPECT_TRUE(parse_osm_height("7m", &m));
  EXPECT_DOUBLE_EQ(m, 7.0);
  EXPECT_TRUE(parse_osm_height("40 ft", &m));
  EXPECT_DOUBLE_EQ(m, 12.192);
  EXPECT_FALSE(parse_osm_height("tall", &m));
  EXPECT_FALSE(parse_osm_height("", &m));
  EXPECT_FALSE(parse_osm_height("-3", &m));
  EXPECT_FALSE(parse_osm_height("12 storeys", &m));
}

TEST(Osm, BuildingsExtrudeToTheirTaggedHeightsAtTheirNodes) {
  Scratch tmp;
  OsmWriter osm;
  struct Expect {
    double base, top;
  };
  std::map<std::int64_t, Expect> expected;
  osm.way(1, osm.box(0, 0, 20, 10), true, {{"building", "yes"}, {"height", "12 m"}});
  expected[1] = {0, 12};
  osm.way(2, osm.box(30, 0, 10, 10), true, {{"building", "apartments"}, {"building:levels", "4"}, {"roof:levels", "1"}});
  expected[2] = {0, 4 * 3.5};
  osm.way(3, osm.box(0, 30, 10, 10), true, {{"building", "yes"}, {"height", "20"}, {"min_height", "5"}});
  expected[3] = {5, 20};
  osm.way(4, osm.box(30, 30, 8, 8), true, {{"building", "yes"}});
  expected[4] = {0, 9.0};  // options.default_height_m
  osm.way(5, osm.box(-30, 0, 8, 8), true, {{"building", "yes"}, {"building:levels", "5"}, {"building:min_level", "2"}});
  expected[5] = {2 * 3.5, 5 * 3.5};
  osm.way(6, osm.box(-30, 30, 8, 8), true, {{"building", "yes"}, {"height", "40 ft"}});
  expected[6] = {0, 12.192};
  osm.way(7, osm.box(60, 0, 5, 5), false, {{"building", "yes"}});  // not closed: rejected
  osm.way(8, osm.box(60, 30, 5, 5), true, {{"highway", "residential"}});  // not a building
  // A courtyard block as a multipolygon: outer ring split into two ways, one inner ring.
  const auto outer = osm.box(0, 60, 30, 30);
  const auto inner = osm.box(10, 70, 10, 10);
  osm.way(20, {outer[0], outer[1], outer[2]}, false, {});
  osm.way(21, {outer[2], outer[3], outer[0]}, false, {});
  osm.way(22, inner, true, {});
  osm.relations << "  <relation id=\"100\" version=\"1\">\n    <member type=\"way\" ref=\"20\" role=\"outer\"/>\n"
                << "    <member type=\"way\" ref=\"22\" role=\"inner\"/>\n    <member type=\"way\" ref=\"21\" role=\"outer\"/>\n"
                << "    <tag k=\"type\" v=\"multipolygon\"/>\n    <tag k=\"building\" v=\"yes\"/>\n"
                << "    <tag k=\"height\" v=\"9\"/>\n  </relation>\n";
  expected[100] = {0, 9};
  const std::string path = write_text(tmp / "city.osm", osm.str());

  LoadOptions options;
  options.origin = kOrigin;
  options.storey_height_m = 3.5;
  options.default_height_m = 9.0;
  LoadReport report;
  const OsmModel model = load_osm(path, options, &report);
  ASSERT_EQ(model.buildings.size(), 7u);
  EXPECT_EQ(report.parts_loaded, 7u);
  ASSERT_EQ(report.rejected.size(), 1u);
  EXPECT_NE(report.rejected[0].find("way 7: footprint is not a closed ring"), std::string::npos) << report.rejected[0];

  const EnuFrame frame(kOrigin);
  for (const OsmBuildingInfo& b : model.buildings) {
    SCOPED_TRACE(b.osm_id);
    ASSERT_TRUE(expected.count(b.osm_id));
    EXPECT_EQ(b.relation, b.osm_id == 100);
    double zmin = 1e9, zmax = -1e9;
    for (std::size_t v = b.first_vertex; v < b.first_vertex + b.num_vertices; ++v) {
      const Eigen::Vector3d& p = model.mesh_W.p_W[v];
      zmin = std::min(zmin, p.z());
      zmax = std::max(zmax, p.z());
      // Every vertex stands on one of the file's nodes: east / north = EnuFrame of that node at the origin height.
      double nearest = 1e9;
      for (const auto& [id, ll] : osm.nodes)
        nearest = std::min(nearest, (frame.from_lla(ll.first, ll.second, kOrigin.alt_m).head<2>() - p.head<2>()).norm());
      EXPECT_LT(nearest, 1e-9);
    }
    EXPECT_DOUBLE_EQ(zmin, expected[b.osm_id].base);
    EXPECT_DOUBLE_EQ(zmax, expected[b.osm_id].top);
  }

  // The loaded triangles of each block close it, facing out: the divergence theorem gives footprint x height.
  std::vector<double> volume(model.buildings.size(), 0.0);
  for (const Eigen::Vector3i& t : model.mesh_W.triangles) {
    for (std::size_t b = 0; b < model.buildings.size(); ++b) {
      const auto& info = model.buildings[b];
      if (static_cast<std::size_t>(t[0]) < info.first_vertex || static_cast<std::size_t>(t[0]) >= info.first_vertex + info.num_vertices)
        continue;
      const auto& p = model.mesh_W.p_W;
      volume[b] += p[t[0]].dot(p[t[1]].cross(p[t[2]])) / 6.0;
    }
  }
  // Footprints are ~w x d metres (the node helper's degrees-per-metre is approximate to ~0.3 %).
  const std::map<std::int64_t, double> footprint_m2{{1, 200}, {2, 100}, {3, 100}, {4, 64}, {5, 64}, {6, 64}, {100, 800}};
  for (std::size_t b = 0; b < model.buildings.size(); ++b) {
    const auto& info = model.buildings[b];
    EXPECT_NEAR(volume[b], footprint_m2.at(info.osm_id) * (info.top_m - info.base_m),
                0.01 * footprint_m2.at(info.osm_id) * info.top_m)
        << info.osm_id;
  }
}

TEST(Osm, DispatcherAndMalformedFiles) {
  Scratch tmp;
  OsmWriter osm;
  osm.way(1, osm.box(0, 0, 10, 10), true, {{"building", "yes"}, {"height", "3"}, {"min_height", "4"}});
  const std::string inverted = write_text(tmp / "inverted.osm", osm.str());
  LoadOptions options;
  options.origin = kOrigin;
  LoadReport report;
  EXPECT_TRUE(load_twin_source(inverted, options, &report).empty());
  ASSERT_EQ(report.rejected.size(), 1u);
  EXPECT_NE(report.rejected[0].find("is not below the top"), std::string::npos) << report.rejected[0];

  const std::string broken = write_text(tmp / "broken.osm", "<?xml version=\"1.0\"?>\n<osm version=\"0.6\">\n<node id=\"1\"\n");
  expect_input_error([&] { load_osm(broken, options); }, broken, "OSM XML error");
  const std::string missing_node = write_text(tmp / "missing.osm",
      "<osm version=\"0.6\">\n<way id=\"5\"><nd ref=\"1\"/><nd ref=\"2\"/><nd ref=\"3\"/><nd ref=\"1\"/>"
      "<tag k=\"building\" v=\"yes\"/></way>\n</osm>\n");
  LoadReport r2;
  EXPECT_TRUE(load_osm(missing_node, options, &r2).mesh_W.empty());
  ASSERT_EQ(r2.rejected.size(), 1u);
  EXPECT_NE(r2.rejected[0].find("node 1 is missing"), std::string::npos) << r2.rejected[0];
}
