#pragma once
// Loading a digital twin from any supported source file into one Mesh in W. The format is chosen by extension
// (and, for .json, by content: a 3D Tiles tileset has "asset"+"root", CityJSON has "type":"CityJSON").
//   .ply .obj                    coordinates in --crs if given, else already in W (a PLY whose header has
//                                `comment twinslam_origin LAT LON ALT` is in the W of that origin: moved through ECEF)
//   .glb .gltf                   glTF y-up converted to z-up; in W (a standalone model) — 3D Tiles content goes through
//                                the tileset loader, which places it in ECEF
//   tileset.json                 OGC 3D Tiles 1.0 / 1.1 (b3dm, glb content), ECEF -> W
//   .json (CityJSON) .city.json  CityJSON 1.0-2.0, CRS from metadata.referenceSystem or --crs
//   .osm                         OSM XML buildings, WGS84 -> W
// Every malformed file throws InputError naming the file and the reason (never crashes); a source that contains
// several parts (3D Tiles content, CityJSON objects) rejects bad parts one by one into LoadReport instead.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "twinslam/twin/geo.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

struct LoadOptions {
  GeoOrigin origin;                 // origin of W
  std::optional<std::string> crs;   // CRS of the source coordinates when the file does not say (--crs)
  double storey_height_m = 3.0;     // OSM: height per building:levels when no height tag [m]
  double default_height_m = 10.0;   // OSM: height of a building with neither height nor levels [m]
  // 3D Tiles: the coarsest tiles whose geometricError is <= this are used (0 = the leaves, the most detailed) [m].
  double max_geometric_error_m = 0.0;
  // 3D Tiles: refuse the quirks of pre-1.0 / non-conforming tilesets (missing geometricError or asset.version,
  // content.url, legacy or unpadded b3dm, CESIUM_RTC) instead of accepting them with a warning as CesiumJS does.
  bool strict = false;
};

struct LoadReport {
  std::size_t parts_loaded = 0;          // tiles, city objects, OSM ways: whatever the format's unit is
  std::vector<std::string> rejected;     // one line per rejected part: "<file>: <reason>"
  std::vector<std::string> warnings;     // one line per quirk and file accepted as CesiumJS does: "<file>: <quirk>"
};

// Throws InputError for an unreadable / unknown / malformed source (naming the file and the problem).
Mesh load_twin_source(const std::string& path, const LoadOptions& options, LoadReport* report = nullptr);

}  // namespace twinslam::twin
