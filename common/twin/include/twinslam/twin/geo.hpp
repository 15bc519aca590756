#pragma once
// Georeferencing of the world frame W. W is East-North-Up at a WGS84 origin (CONTRACTS.md): GeographicLib's
// LocalCartesian does ECEF <-> ENU exactly; PROJ converts projected or compound CRSs (EPSG:2056 Swiss LV95,
// EPSG:28992 / 7415 Dutch RD (+NAP), UTM zones, ...) to WGS84 geographic coordinates first.
#include <memory>
#include <string>

#include <Eigen/Core>

namespace twinslam::twin {

struct GeoOrigin {
  double lat_deg = 0.0;  // WGS84 latitude [deg]
  double lon_deg = 0.0;  // WGS84 longitude [deg]
  double alt_m = 0.0;    // ellipsoidal height [m]
};

// "LAT,LON,ALT" (degrees, degrees, metres) as given on the command line; throws UsageError naming the problem.
GeoOrigin parse_origin(const std::string& text);

// The ENU frame W at an origin.
class EnuFrame {
 public:
  explicit EnuFrame(const GeoOrigin& origin);
  ~EnuFrame();
  EnuFrame(const EnuFrame&) = delete;
  EnuFrame& operator=(const EnuFrame&) = delete;

  const GeoOrigin& origin() const { return origin_; }
  Eigen::Vector3d from_ecef(const Eigen::Vector3d& p_ecef) const;   // [m ECEF] -> p_W [m]
  Eigen::Vector3d to_ecef(const Eigen::Vector3d& p_W) const;
  Eigen::Vector3d from_lla(double lat_deg, double lon_deg, double h_m) const;  // WGS84 -> p_W
  Eigen::Vector3d to_lla(const Eigen::Vector3d& p_W) const;          // p_W -> (lat [deg], lon [deg], h [m])
  // Rotation R_W_ECEF (columns: ECEF axes in W) at the origin: turns ECEF directions into W directions.
  Eigen::Matrix3d R_W_ECEF() const;

 private:
  GeoOrigin origin_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Coordinates of a source CRS -> WGS84 (lat [deg], lon [deg], ellipsoidal h [m]) through PROJ. Axis order is
// normalized to (easting, northing, height) for projected CRSs and (lon, lat, h) for geographic ones
// (proj_normalize_for_visualization), whatever the EPSG definition says. A CRS without a vertical part keeps h as given.
class CrsTransform {
 public:
  // crs: "EPSG:2056", "urn:ogc:def:crs:EPSG::7415", "https://www.opengis.net/def/crs/EPSG/0/7415", or any string PROJ
  // accepts. Throws InputError "unknown CRS '<crs>': <PROJ's reason>".
  explicit CrsTransform(const std::string& crs);
  ~CrsTransform();
  CrsTransform(const CrsTransform&) = delete;
  CrsTransform& operator=(const CrsTransform&) = delete;

  Eigen::Vector3d to_lla(const Eigen::Vector3d& xyz) const;  // (lat [deg], lon [deg], h [m]); throws InputError on failure
  const std::string& crs() const { return crs_; }
  // How heights are converted: a compound CRS whose vertical datum has no geoid grid here (EPSG:7415 NAP) gets its
  // height treated as EGM96 height (see crs.cpp); this names the method used, for logs and tests.
  const std::string& method() const;

 private:
  std::string crs_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace twinslam::twin
