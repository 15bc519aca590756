#pragma once
// `twinslam export` (CONTRACTS.md "Exports"): a run's tracks placed on Earth through W's origin - GeoJSON (RFC 7946)
// and KML 2.2 - for maps and Google Earth. W is East-North-Up at the origin (twin/geo.hpp), so every position goes
// W -> ECEF -> WGS84 exactly (GeographicLib); nothing is projected.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "twinslam/trajectory/trajectory.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::cli {

struct GeoTrack {
  std::string name;                    // "estimate", "gnss", "ground_truth"
  std::vector<std::int64_t> stamps_ns;
  std::vector<Eigen::Vector3d> lla;    // per stamp: latitude [deg], longitude [deg], WGS84 ellipsoidal height [m]
};

// The positions p_WB of a trajectory in W, converted through the ENU frame W.
GeoTrack track_from_W(std::string name, const Trajectory& trajectory_W, const twin::EnuFrame& W);

// A FeatureCollection with one LineString Feature per track with >= 2 positions ([lon, lat, h], h ellipsoidal, full
// double precision) and properties name, stamps_s (seconds, the dataset clock), height datum and the origin.
nlohmann::json tracks_geojson(const std::vector<GeoTrack>& tracks, const twin::GeoOrigin& origin);

// A KML 2.2 document with one Placemark (LineString, altitudeMode absolute) per track with >= 2 positions. KML
// altitudes are above mean sea level: each is h - geoid_height(lat, lon) (EGM96 undulation [m]).
std::string tracks_kml(const std::vector<GeoTrack>& tracks,
                       const std::function<double(double lat_deg, double lon_deg)>& geoid_height);

}  // namespace twinslam::cli
