#pragma once
// CityJSON 1.0 / 1.1 / 2.0 city models -> one Mesh in W. Vertices are decoded with `transform` (scale, translate),
// taken from the CRS of metadata.referenceSystem ("urn:ogc:def:crs:EPSG::7415", "https://www.opengis.net/def/crs/EPSG/
// 0/7415", ...) or else LoadOptions::crs, through CrsTransform to WGS84 and EnuFrame into W. Geometry types
// MultiSurface, CompositeSurface, Solid, MultiSolid and CompositeSolid are triangulated (holes included) with
// triangulate_polygon; each surface keeps its ring orientation, so solids' outer shells face outwards.
// Level of detail: per city object only its geometries of the highest LoD are used (an LoD2 solid and its LoD1 box
// would otherwise overlap in the twin). Points, lines and GeometryInstance (templates) carry no surfaces and are
// skipped with a note in LoadReport::rejected; a city object whose geometry is malformed (index out of range, bad
// nesting) is rejected with its reason, and the rest still loads.
#include <string>
#include <vector>

#include "twinslam/twin/load.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

struct CityObjectInfo {
  std::string id;
  std::string type;            // "Building", "BuildingPart", "Road", ...
  std::string lod;             // the LoD used, as written ("2", "2.2")
  std::vector<std::string> parents;  // ids of its parent objects (a BuildingPart's Building), as the file lists them
  std::size_t first_triangle = 0;
  std::size_t num_triangles = 0;
};

struct CityJsonModel {
  Mesh mesh_W;
  std::vector<CityObjectInfo> objects;  // the loaded objects (with triangles), in the file's key order
  std::string crs;                       // the CRS used
};

// Throws InputError "<path>: <reason>" for unreadable JSON, a file that is not CityJSON, an unsupported version,
// malformed vertices / transform, no CRS (neither in the file nor in options), or an unknown CRS.
// report: parts_loaded += loaded objects; rejected += one line per rejected object or skipped geometry.
CityJsonModel load_cityjson(const std::string& path, const LoadOptions& options, LoadReport* report = nullptr);

}  // namespace twinslam::twin
