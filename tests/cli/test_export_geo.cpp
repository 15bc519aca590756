// `twinslam export`'s GeoJSON and KML writers: every position lands where an independent conversion (PROJ) puts it.
#include <cmath>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "export_geo.hpp"
#include "proj_enu.hpp"

namespace twinslam::cli {
namespace {

const twin::GeoOrigin kOrigin{47.3769, 8.5417, 408.0};

Trajectory flight() {
  Trajectory t;
  for (int k = 0; k < 50; ++k) {
    StampedPose p;
    p.stamp_ns = 1'000'000'000'000'000'000 + k * 100'000'000LL;
    // A few hundred metres out and up, so an error in the ENU rotation or the height would show.
    p.T_XB.translation() = Eigen::Vector3d(-300.0 + 13.7 * k, 250.0 - 7.1 * k, 12.0 + 0.9 * k);
    t.poses.push_back(p);
  }
  return t;
}

TEST(ExportGeo, GeoJsonPositionsMatchAnIndependentConversionWithinACentimetre) {
  const twin::EnuFrame W(kOrigin);
  const test::ProjEnu proj(kOrigin.lat_deg, kOrigin.lon_deg, kOrigin.alt_m);
  const Trajectory t = flight();
  const nlohmann::json j = tracks_geojson({track_from_W("estimate", t, W)}, kOrigin);
  ASSERT_EQ(j["type"], "FeatureCollection");
  ASSERT_EQ(j["features"].size(), 1u);
  const auto& f = j["features"][0];
  EXPECT_EQ(f["geometry"]["type"], "LineString");
  EXPECT_EQ(f["properties"]["name"], "estimate");
  const auto& c = f["geometry"]["coordinates"];
  ASSERT_EQ(c.size(), t.poses.size());
  for (std::size_t i = 0; i < t.poses.size(); ++i) {
    const Eigen::Vector3d expected = proj.to_lla(t.poses[i].p_X());
    const Eigen::Vector3d got(c[i][1].get<double>(), c[i][0].get<double>(), c[i][2].get<double>());  // lon first
    EXPECT_LT(test::lla_distance_m(expected, got), 0.01) << "pose " << i;
    EXPECT_NEAR(f["properties"]["stamps_s"][i].get<double>(), 1e-9 * t.poses[i].stamp_ns, 1e-6);
  }
}

TEST(ExportGeo, KmlAltitudesAreAboveTheGeoidAndPositionsLongitudeFirst) {
  const twin::EnuFrame W(kOrigin);
  const test::ProjEnu proj(kOrigin.lat_deg, kOrigin.lon_deg, kOrigin.alt_m);
  const Trajectory t = flight();
  const std::string kml = tracks_kml({track_from_W("estimate", t, W)}, [](double, double) { return 47.5; });
  EXPECT_NE(kml.find("<kml xmlns=\"http://www.opengis.net/kml/2.2\">"), std::string::npos);
  EXPECT_NE(kml.find("<altitudeMode>absolute</altitudeMode>"), std::string::npos);
  const std::regex position(R"(([-0-9.]+),([-0-9.]+),([-0-9.]+)\n)");
  std::vector<Eigen::Vector3d> got;
  for (auto it = std::sregex_iterator(kml.begin(), kml.end(), position); it != std::sregex_iterator(); ++it) {
    got.emplace_back(std::stod((*it)[2]), std::stod((*it)[1]), std::stod((*it)[3]) + 47.5);
  }
  ASSERT_EQ(got.size(), t.poses.size());
  EXPECT_LT(test::lla_distance_m(proj.to_lla(t.poses.front().p_X()), got.front()), 0.01);
  EXPECT_LT(test::lla_distance_m(proj.to_lla(t.poses.back().p_X()), got.back()), 0.01);
}

TEST(ExportGeo, TracksWithFewerThanTwoPositionsAreLeftOut) {
  // RFC 7946: a LineString has two or more positions; a dataset without GNSS gives an empty track.
  const twin::EnuFrame W(kOrigin);
  Trajectory one;
  one.poses.push_back({});
  const std::vector<GeoTrack> tracks{track_from_W("estimate", flight(), W), GeoTrack{"gnss", {}, {}},
                                     track_from_W("ground_truth", one, W)};
  const nlohmann::json j = tracks_geojson(tracks, kOrigin);
  ASSERT_EQ(j["features"].size(), 1u);
  EXPECT_EQ(j["features"][0]["properties"]["name"], "estimate");
  const std::string kml = tracks_kml(tracks, [](double, double) { return 0.0; });
  EXPECT_EQ(kml.find("<name>gnss</name>"), std::string::npos);
  EXPECT_NE(kml.find("<name>estimate</name>"), std::string::npos);
}

}  // namespace
}  // namespace twinslam::cli
