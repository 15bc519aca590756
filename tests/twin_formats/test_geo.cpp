// Georeferencing of W: ENU at a WGS84 origin (GeographicLib) and projected / compound CRSs through PROJ.
#include <gtest/gtest.h>

#include <GeographicLib/Geocentric.hpp>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/geo.hpp"

using namespace twinslam;
using namespace twinslam::twin;

namespace {
// Horizontal distance [m] between two WGS84 positions (small-distance approximation, fine for < 1 km).
double ground_distance_m(double lat1, double lon1, double lat2, double lon2) {
  const double kDegToM = 111320.0;
  const double dn = (lat1 - lat2) * kDegToM;
  const double de = (lon1 - lon2) * kDegToM * std::cos(lat1 * M_PI / 180.0);
  return std::hypot(dn, de);
}
}  // namespace

TEST(Geo, ParseOriginAcceptsLatLonAltAndRejectsGarbage) {
  const GeoOrigin o = parse_origin("47.3769,8.5417,408");
  EXPECT_DOUBLE_EQ(o.lat_deg, 47.3769);
  EXPECT_DOUBLE_EQ(o.lon_deg, 8.5417);
  EXPECT_DOUBLE_EQ(o.alt_m, 408.0);
  EXPECT_THROW(parse_origin("47.3769,8.5417"), UsageError);
  EXPECT_THROW(parse_origin("95,8,0"), UsageError);
  EXPECT_THROW(parse_origin("47,8,0,1"), UsageError);
  EXPECT_THROW(parse_origin("a,b,c"), UsageError);
}

TEST(Geo, EnuEcefRoundTripIsExact) {
  const EnuFrame frame({47.3769, 8.5417, 408.0});
  for (const Eigen::Vector3d& p_W : std::vector<Eigen::Vector3d>{{0, 0, 0}, {1234.5, -987.6, 55.5},
                                                        {-20000, 15000, -300}}) {
    EXPECT_LT((frame.from_ecef(frame.to_ecef(p_W)) - p_W).norm(), 1e-6);
    const Eigen::Vector3d lla = frame.to_lla(p_W);
    EXPECT_LT((frame.from_lla(lla.x(), lla.y(), lla.z()) - p_W).norm(), 1e-6);
  }
  // The origin itself is (0, 0, 0) and its ECEF position is GeographicLib's.
  Eigen::Vector3d o_ecef;
  GeographicLib::Geocentric::WGS84().Forward(47.3769, 8.5417, 408.0, o_ecef.x(), o_ecef.y(), o_ecef.z());
  EXPECT_LT(frame.from_ecef(o_ecef).norm(), 1e-6);
  // R_W_ECEF turns ECEF's up at the origin (the ellipsoid normal) into W's z.
  const Eigen::Vector3d up_ecef = frame.to_ecef({0, 0, 1}) - o_ecef;
  EXPECT_LT((frame.R_W_ECEF() * up_ecef - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
}

TEST(Geo, PointNorthOfTheOriginIsOnThePositiveNorthAxis) {
  const EnuFrame frame({47.3769, 8.5417, 408.0});
  // 100 m north along the meridian: latitude grows by 100 m / M, M = meridional radius of curvature there.
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  const double s = std::sin(47.3769 * M_PI / 180.0);
  const double M = a * (1 - e2) / std::pow(1 - e2 * s * s, 1.5);
  const double dlat_deg = 100.0 / (M + 408.0) * 180.0 / M_PI;
  const Eigen::Vector3d p = frame.from_lla(47.3769 + dlat_deg, 8.5417, 408.0);
  EXPECT_NEAR(p.x(), 0.0, 1e-6);
  EXPECT_NEAR(p.y(), 100.0, 1e-3);
  EXPECT_NEAR(p.z(), -100.0 * 100.0 / (2 * (M + 408.0)), 1e-3);  // the ellipsoid curves down by d^2 / 2R (~0.8 mm)
}

TEST(Geo, SwissLv95BernObservatory) {
  const CrsTransform lv95("EPSG:2056");
  const Eigen::Vector3d lla = lv95.to_lla({2600000.0, 1200000.0, 500.0});
  // The LV95 origin (false easting/northing) is the old Bern observatory: 46°57'08.66" N 7°26'22.50" E on CH1903's
  // Bessel ellipsoid, 46°57'03.9" N 7°26'19.1" E in WGS84 (swisstopo); the datum shift is ~160 m.
  EXPECT_LT(ground_distance_m(lla.x(), lla.y(), 46.0 + 57.0 / 60 + 3.9 / 3600, 7.0 + 26.0 / 60 + 19.1 / 3600), 1.0);
  EXPECT_DOUBLE_EQ(lla.z(), 500.0);  // no vertical part: h kept as given
}

TEST(Geo, DutchRdAmersfoortReference) {
  const CrsTransform rd("EPSG:28992");
  const Eigen::Vector3d lla = rd.to_lla({155000.0, 463000.0, 0.0});
  // RD's origin, the Amersfoort tower: 52.15517440 N, 5.38720621 E in ETRS89/WGS84 (52.1562 N, 5.3876 E on Bessel).
  EXPECT_LT(ground_distance_m(lla.x(), lla.y(), 52.15517440, 5.38720621), 1.0);
  // The URN and URL spellings of CityJSON's metadata.referenceSystem name the same CRS.
  const CrsTransform urn("urn:ogc:def:crs:EPSG::28992");
  const CrsTransform url("https://www.opengis.net/def/crs/EPSG/0/28992");
  EXPECT_LT((urn.to_lla({155000.0, 463000.0, 0.0}) - lla).norm(), 1e-9);
  EXPECT_LT((url.to_lla({155000.0, 463000.0, 0.0}) - lla).norm(), 1e-9);
}

TEST(Geo, CompoundRdNapWithoutGeoidGridUsesEgm96Heights) {
  // PROJ's own choice here (no NLGEO grid) would be a ballpark: ~110 m off horizontally and h = NAP height.
  const CrsTransform rdnap("urn:ogc:def:crs:EPSG::7415");
  const Eigen::Vector3d lla = rdnap.to_lla({155000.0, 463000.0, 0.0});
  EXPECT_LT(ground_distance_m(lla.x(), lla.y(), 52.15517440, 5.38720621), 1.0);
  // NAP 0 m at Amersfoort lies ~43.3 m above the WGS84 ellipsoid (quasi-geoid NLGEO2018: 43.2-43.4 m there).
  EXPECT_NEAR(lla.z(), 43.3, 1.5);
  EXPECT_NE(rdnap.method().find("EGM96"), std::string::npos) << rdnap.method();
}

TEST(Geo, Utm32North) {
  const CrsTransform utm("EPSG:32632");
  // The central meridian of zone 32 is 9° E; easting 500000 lies on it.
  const Eigen::Vector3d lla = utm.to_lla({500000.0, 5000000.0, 10.0});
  EXPECT_NEAR(lla.y(), 9.0, 1e-9);
  EXPECT_NEAR(lla.x(), 45.1535, 1e-3);  // 5000 km of meridian arc (scale 0.9996) from the equator
  // Round trip through W: a point 1 km east of a UTM origin is ~1 km east in W.
  const Eigen::Vector3d lla_e = utm.to_lla({501000.0, 5000000.0, 10.0});
  const EnuFrame frame({lla.x(), lla.y(), 10.0});
  const Eigen::Vector3d p = frame.from_lla(lla_e.x(), lla_e.y(), lla_e.z());
  EXPECT_NEAR(p.x(), 1000.0 / 0.9996, 0.5);
  EXPECT_NEAR(p.y(), 0.0, 0.5);
}

TEST(Geo, UnknownCrsIsAnInputErrorNamingIt) {
  try {
    CrsTransform bad("EPSG:999999");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown CRS 'EPSG:999999': not in PROJ's database"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(CrsTransform("not a crs"), InputError);
}

TEST(Geo, GeographicCrsTakesLonLatOrder) {
  // EPSG:4326 is (lat, lon) by definition; normalized for visualization the input is (lon, lat) like every other
  // CRS's (easting, northing). A 2D geographic CRS keeps h as given.
  const CrsTransform wgs84("EPSG:4326");
  const Eigen::Vector3d lla = wgs84.to_lla({8.5417, 47.3769, 408.0});
  EXPECT_NEAR(lla.x(), 47.3769, 1e-12);
  EXPECT_NEAR(lla.y(), 8.5417, 1e-12);
  EXPECT_NEAR(lla.z(), 408.0, 1e-9);
  EXPECT_THROW(wgs84.to_lla({8.5, std::nan(""), 0.0}), InputError);
}
