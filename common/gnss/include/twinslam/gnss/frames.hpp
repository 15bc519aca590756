#pragma once
// Earth frames for GNSS: WGS84 geodetic <-> ECEF (GeographicLib), the local ENU frame at a point, and a satellite's
// elevation and azimuth seen from a receiver.
#include <Eigen/Core>

namespace twinslam::gnss {

struct Geodetic {
  double latitude_deg = 0, longitude_deg = 0, height_m = 0;  // WGS84, ellipsoidal height
};

Eigen::Vector3d geodetic_to_ecef(const Geodetic& g);
Geodetic ecef_to_geodetic(const Eigen::Vector3d& p_ecef);

// R_ENU_ECEF at geodetic latitude/longitude: rotates ECEF vectors into East-North-Up there.
Eigen::Matrix3d rotation_enu_from_ecef(double latitude_deg, double longitude_deg);

struct LookAngles {
  double elevation_deg = 0;  // above the local horizon (ellipsoid normal) [deg]
  double azimuth_deg = 0;    // clockwise from north [deg], in [0, 360)
};
LookAngles look_angles(const Eigen::Vector3d& receiver_ecef, const Eigen::Vector3d& satellite_ecef);

}  // namespace twinslam::gnss
