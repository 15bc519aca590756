#pragma once
// Private to the OSM loader: the parts of an OSM XML file a building needs, as plain data.
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace twinslam::twin {

struct OsmNode {
  double lat_deg = 0.0, lon_deg = 0.0;
};

struct OsmWay {
  std::int64_t id = 0;
  std::vector<std::int64_t> refs;
  std::map<std::string, std::string> tags;  // only kept for ways with a building tag
};

struct OsmMember {
  std::int64_t way = 0;
  std::string role;  // "outer" / "inner" / ""
};

struct OsmRelation {
  std::int64_t id = 0;
  std::vector<OsmMember> ways;
  std::map<std::string, std::string> tags;
};

struct OsmData {
  std::unordered_map<std::int64_t, OsmNode> nodes;
  std::vector<OsmWay> ways;                         // every way (multipolygon members need untagged ones too)
  std::vector<OsmRelation> building_relations;      // type=multipolygon with a building tag
};

// Throws InputError naming the file and the reason.
OsmData read_osm_xml(const std::string& path);

}  // namespace twinslam::twin
