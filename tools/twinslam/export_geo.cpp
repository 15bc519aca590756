#include "export_geo.hpp"

#include <cstdio>

namespace twinslam::cli {

GeoTrack track_from_W(std::string name, const Trajectory& trajectory_W, const twin::EnuFrame& W) {
  GeoTrack track{std::move(name), {}, {}};
  track.stamps_ns.reserve(trajectory_W.poses.size());
  track.lla.reserve(trajectory_W.poses.size());
  for (const auto& pose : trajectory_W.poses) {
    track.stamps_ns.push_back(pose.stamp_ns);
    track.lla.push_back(W.to_lla(pose.p_X()));
  }
  return track;
}

nlohmann::json tracks_geojson(const std::vector<GeoTrack>& tracks, const twin::GeoOrigin& origin) {
  nlohmann::json features = nlohmann::json::array();
  for (const GeoTrack& t : tracks) {
    if (t.lla.size() < 2) continue;  // RFC 7946 3.1.4: a LineString has two or more positions
    nlohmann::json coordinates = nlohmann::json::array(), stamps = nlohmann::json::array();
    for (std::size_t i = 0; i < t.lla.size(); ++i) {
      coordinates.push_back({t.lla[i].y(), t.lla[i].x(), t.lla[i].z()});  // RFC 7946: longitude first
      // Seconds, not ns: JSON readers in JavaScript hold integers exactly only up to 2^53 (~1e16).
      stamps.push_back(1e-9 * static_cast<double>(t.stamps_ns[i]));
    }
    features.push_back({{"type", "Feature"},
                        {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coordinates)}}},
                        {"properties",
                         {{"name", t.name},
                          {"stamps_s", std::move(stamps)},
                          {"height", "WGS84 ellipsoidal [m]"},
                          {"origin", {origin.lat_deg, origin.lon_deg, origin.alt_m}}}}});
  }
  return {{"type", "FeatureCollection"}, {"features", std::move(features)}};
}

namespace {
// A KML colour (aabbggrr) per track, so the three lines can be told apart in Google Earth.
const char* kml_colour(const std::string& name) {
  if (name == "estimate") return "ff0000ff";      // red
  if (name == "gnss") return "ff00ffff";          // yellow
  return "ff00ff00";                              // ground truth and others: green
}
}  // namespace

std::string tracks_kml(const std::vector<GeoTrack>& tracks,
                       const std::function<double(double lat_deg, double lon_deg)>& geoid_height) {
  std::string kml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n"
                    "<Document>\n<name>twinslam run</name>\n";
  for (const GeoTrack& t : tracks) {
    if (t.lla.size() < 2) continue;
    kml += "<Placemark>\n<name>" + t.name + "</name>\n<Style><LineStyle><color>" + kml_colour(t.name) +
           "</color><width>3</width></LineStyle></Style>\n<LineString>\n<altitudeMode>absolute</altitudeMode>\n"
           "<coordinates>\n";
    char position[96];
    for (const Eigen::Vector3d& p : t.lla) {
      std::snprintf(position, sizeof position, "%.10f,%.10f,%.3f\n", p.y(), p.x(), p.z() - geoid_height(p.x(), p.y()));
      kml += position;
    }
    kml += "</coordinates>\n</LineString>\n</Placemark>\n";
  }
  return kml + "</Document>\n</kml>\n";
}

}  // namespace twinslam::cli
