#include "twinslam/gnss/frames.hpp"

#include <cmath>
#include <numbers>

#include <GeographicLib/Geocentric.hpp>

namespace twinslam::gnss {

Eigen::Vector3d geodetic_to_ecef(const Geodetic& g) {
  Eigen::Vector3d p;
  GeographicLib::Geocentric::WGS84().Forward(g.latitude_deg, g.longitude_deg, g.height_m, p.x(), p.y(), p.z());
  return p;
}

Geodetic ecef_to_geodetic(const Eigen::Vector3d& p_ecef) {
  Geodetic g;
  GeographicLib::Geocentric::WGS84().Reverse(p_ecef.x(), p_ecef.y(), p_ecef.z(), g.latitude_deg, g.longitude_deg,
                                             g.height_m);
  return g;
}

Eigen::Matrix3d rotation_enu_from_ecef(double latitude_deg, double longitude_deg) {
  const double lat = latitude_deg * std::numbers::pi / 180, lon = longitude_deg * std::numbers::pi / 180;
  const double sl = std::sin(lat), cl = std::cos(lat), so = std::sin(lon), co = std::cos(lon);
  Eigen::Matrix3d R;
  R << -so, co, 0,             //
      -sl * co, -sl * so, cl,  //
      cl * co, cl * so, sl;
  return R;
}

LookAngles look_angles(const Eigen::Vector3d& receiver_ecef, const Eigen::Vector3d& satellite_ecef) {
  const Geodetic g = ecef_to_geodetic(receiver_ecef);
  const Eigen::Vector3d d = rotation_enu_from_ecef(g.latitude_deg, g.longitude_deg) * (satellite_ecef - receiver_ecef);
  LookAngles a;
  a.elevation_deg = std::atan2(d.z(), d.head<2>().norm()) * 180 / std::numbers::pi;
  a.azimuth_deg = std::atan2(d.x(), d.y()) * 180 / std::numbers::pi;
  if (a.azimuth_deg < 0) a.azimuth_deg += 360;
  return a;
}

}  // namespace twinslam::gnss
