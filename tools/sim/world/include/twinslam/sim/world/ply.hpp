#pragma once
// Binary little-endian PLY for world and twin meshes: double vertices in W (ENU, metres), per face the vertex list,
// building_id (int) and kind (uchar, SurfaceKind). The georeference of W rides in a header comment
//   comment twinslam_origin LAT LON ALT
// (WGS84 degrees and metres, 17 significant digits) so a twin file is self-describing.
#include <string>

#include "twinslam/sim/scenario.hpp"
#include "twinslam/sim/world/mesh.hpp"

namespace twinslam::sim {

// Throws InputError if the file cannot be written.
void write_ply(const std::string& path, const TriMesh& mesh, const Origin& origin);

struct PlyMesh {
  TriMesh mesh;
  Origin origin;
  bool has_origin = false;  // false when the file has no twinslam_origin comment
};

// Reads what write_ply writes; also accepts float vertices and faces without building_id/kind (then kNoBuilding and
// kFacade), triangles only. Throws InputError naming the file and the problem for anything else.
PlyMesh read_ply(const std::string& path);

}  // namespace twinslam::sim
