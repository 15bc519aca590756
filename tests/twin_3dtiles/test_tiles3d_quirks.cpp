// Real-world 3D Tiles quirks (issue 15, item 5): a pre-1.0 tileset as old exporters wrote it loads like its
// conforming twin, with one warning line per quirk and file; strict mode refuses each quirk.
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "tiles_test_utils.hpp"
#include "twinslam/twin/tiles3d.hpp"

using namespace twinslam::twin;
using namespace tiles_test;

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;
const GeoOrigin kOrigin{0.698874 * kDeg, -1.31968 * kDeg, 0.0};

LoadOptions options(bool strict) {
  LoadOptions o;
  o.origin = kOrigin;
  o.strict = strict;
  return o;
}

const std::string kCity = sample("cesium-samples/TilesetWithRequestVolume/city/");
const std::string kSphere = R"("boundingVolume":{"sphere":[0,0,0,1e7]})";

// The sample city's lr / ur tiles (ll and ul are unpadded: a quirk of their own) under a root, written once as the spec wants and once as a pre-1.0 exporter did:
// asset.version "0.0" and none at all, no refine on the root, children without geometricError, content.url.
std::string conforming() {
  return R"({"asset":{"version":"1.0"},"geometricError":100,"root":{)" + kSphere +
         R"(,"geometricError":20,"refine":"REPLACE","children":[{)" + kSphere + R"(,"geometricError":0,"content":{"uri":")" +
         kCity + R"(lr.b3dm"}},{)" + kSphere + R"(,"geometricError":0,"content":{"uri":")" + kCity + R"(ur.b3dm"}}]}})";
}
std::string quirky(const std::string& asset) {
  return R"({"asset":)" + asset + R"(,"geometricError":100,"root":{)" + kSphere +
         R"(,"geometricError":20,"children":[{)" + kSphere + R"(,"content":{"url":")" + kCity + R"(lr.b3dm"}},{)" +
         kSphere + R"(,"content":{"url":")" + kCity + R"(ur.b3dm"}}]}})";
}

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const std::string& l : lines) all += l + "\n";
  return all;
}

}  // namespace

TEST(Tiles3dQuirks, APreReleaseTilesetLoadsLikeItsConformingTwinWithOneWarningPerQuirk) {
  Scratch tmp("quirks");
  write_text(tmp.path("good.json"), conforming());
  write_text(tmp.path("old.json"), quirky(R"({"version":"0.0"})"));
  write_text(tmp.path("nover.json"), quirky(R"({"generator":"x"})"));
  LoadReport good_report;
  const Mesh good = load_3dtiles(tmp.path("good.json"), options(false), &good_report);
  EXPECT_TRUE(good_report.warnings.empty()) << joined(good_report.warnings);
  ASSERT_GT(good.num_triangles(), 0u);
  for (const char* file : {"old.json", "nover.json"}) {
    LoadReport report;
    const Mesh m = load_3dtiles(tmp.path(file), options(false), &report);
    ASSERT_EQ(m.num_vertices(), good.num_vertices()) << file;  // children at 0 (the parent's 20 > tau 0: refined)
    for (std::size_t i = 0; i < m.num_vertices(); ++i) ASSERT_EQ(m.p_W[i], good.p_W[i]) << file << " " << i;
    EXPECT_TRUE(report.rejected.empty()) << joined(report.rejected);
    // Two children lack geometricError and two use url: still one line each for this file.
    const std::string all = joined(report.warnings);
    ASSERT_EQ(report.warnings.size(), 4u) << all;
    EXPECT_NE(all.find(std::string(file) + ": tile without geometricError (first at root/0); the parent's value"),
              std::string::npos) << all;
    EXPECT_NE(all.find("content.url (pre-1.0) instead of content.uri (first at root/0)"), std::string::npos) << all;
    EXPECT_NE(all.find("root tile without refine"), std::string::npos) << all;
    EXPECT_NE(all.find(file == std::string("old.json") ? "asset.version 0.0" : "without asset.version"),
              std::string::npos) << all;
  }
}

TEST(Tiles3dQuirks, AMissingGeometricErrorTakesTheParentsValueForTheLevelChoice) {
  // Root 20 without children errors given: they inherit 20, so with tau = 25 the root's own content is enough and
  // with tau = 10 the children (leaves) replace it.
  Scratch tmp("inherit");
  const std::string children = R"(,"children":[{)" + kSphere + R"(,"content":{"uri":")" + kCity + R"(ur.b3dm"}}]})";
  write_text(tmp.path("t.json"), R"({"asset":{"version":"1.0"},"root":{)" + kSphere +
                                     R"(,"geometricError":20,"refine":"REPLACE","content":{"uri":")" + kCity +
                                     R"(lr.b3dm"})" + children + "}");
  auto names = [&](double tau) {
    std::string s;
    for (const TileContentRef& c : select_3dtiles_contents(tmp.path("t.json"), tau, nullptr)) {
      s += c.path.substr(c.path.size() - 7) + " ";
    }
    return s;
  };
  EXPECT_EQ(names(25), "lr.b3dm ");
  EXPECT_EQ(names(10), "ur.b3dm ");
  // A root without geometricError in a tileset without one has nothing to inherit: refused, naming the tile.
  write_text(tmp.path("none.json"), R"({"asset":{"version":"1.0"},"root":{)" + kSphere + "}}");
  expect_input_error([&] { select_3dtiles_contents(tmp.path("none.json"), 0, nullptr); },
                     {"none.json", "root: geometricError missing"});
}

TEST(Tiles3dQuirks, StrictModeRefusesEachQuirk) {
  Scratch tmp("strict");
  write_text(tmp.path("old.json"), quirky(R"({"version":"0.0"})"));
  expect_input_error([&] { load_3dtiles(tmp.path("old.json"), options(true), nullptr); },
                     {"old.json", "asset.version 0.0", "refused in strict mode"});
  write_text(tmp.path("good.json"), conforming());
  LoadReport report;
  EXPECT_GT(load_3dtiles(tmp.path("good.json"), options(true), &report).num_triangles(), 0u);
  EXPECT_TRUE(report.warnings.empty() && report.rejected.empty());
  // Content quirks too, and they fail the whole load (not just that part): the legacy-header sample tile, and the
  // sample city's unpadded ll.b3dm.
  const std::string legacy = sample("cesium-tools/Batched/BatchedDeprecated1/tileset.json");
  LoadReport lenient;
  EXPECT_GT(load_3dtiles(legacy, options(false), &lenient).num_triangles(), 0u);
  EXPECT_NE(joined(lenient.warnings).find("batchedDeprecated1.b3dm: legacy b3dm header"), std::string::npos)
      << joined(lenient.warnings);
  expect_input_error([&] { load_3dtiles(legacy, options(true), nullptr); },
                     {"batchedDeprecated1.b3dm", "legacy b3dm header (20 / 24 bytes) (refused in strict mode)"});
  write_text(tmp.path("ll.json"), R"({"asset":{"version":"1.0"},"root":{)" + kSphere +
                                      R"(,"geometricError":0,"refine":"ADD","content":{"uri":")" + kCity + R"(ll.b3dm"}}})");
  expect_input_error([&] { load_3dtiles(tmp.path("ll.json"), options(true), nullptr); },
                     {"ll.b3dm: byteLength: b3dm byteLength not a multiple of 8 (refused in strict mode)"});
  // In an external tileset as well (elsewhere a bad external tileset is one rejected part).
  write_text(tmp.path("ext.json"), quirky(R"({"version":"1.0"})"));
  write_text(tmp.path("root.json"), R"({"asset":{"version":"1.0"},"root":{)" + kSphere +
                                        R"(,"geometricError":50,"refine":"ADD","content":{"uri":"ext.json"}}})");
  expect_input_error([&] { load_3dtiles(tmp.path("root.json"), options(true), nullptr); },
                     {"ext.json", "refused in strict mode"});
}
