#pragma once
// OSM XML buildings -> extruded block models in W (libosmium's XML reader).
// Buildings: closed ways with a `building` tag, and multipolygon relations (type=multipolygon + building) whose
// outer / inner member ways join into closed rings (courtyards become holes). `building:part` ways are not read.
// Height [m]: `height` ("12", "12.5", "12 m", "40 ft", "40'"), else `building:levels` x storey_height_m, else
// default_height_m; `roof:levels` is ignored (flat roofs only). Base: `min_height`, else `building:min_level` x
// storey_height_m, else 0. Ground: W's z = 0 (the origin's altitude) under every building — OSM has no terrain, so
// the twin is flat at the origin's height; the footprint's east / north come from EnuFrame::from_lla of the nodes.
// Geometry per building: walls (outward-facing), a flat roof cap with holes (triangulate_polygon), and a bottom cap
// only when the base is above ground (a part on stilts or a bridge; a ground-level bottom is never seen).
// A building with a bad footprint (unclosed, < 3 distinct nodes, missing node, zero area, base >= top) is rejected
// into LoadReport with its reason; XML errors throw InputError.
#include <cstdint>
#include <string>
#include <vector>

#include "twinslam/twin/load.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

struct OsmBuildingInfo {
  std::int64_t osm_id = 0;
  bool relation = false;        // a multipolygon relation (else a way)
  double base_m = 0.0;          // bottom z in W [m]
  double top_m = 0.0;           // roof z in W [m]
  std::size_t first_vertex = 0;
  std::size_t num_vertices = 0;
};

struct OsmModel {
  Mesh mesh_W;
  std::vector<OsmBuildingInfo> buildings;  // ways first (file order), then relations
};

// Throws InputError "<path>: <reason>" for an unreadable or malformed file.
OsmModel load_osm(const std::string& path, const LoadOptions& options, LoadReport* report = nullptr);

// A height tag in metres ("12", "12.5 m", "40 ft", "40'"); false if it is not a height.
bool parse_osm_height(const std::string& text, double* metres);

}  // namespace twinslam::twin
