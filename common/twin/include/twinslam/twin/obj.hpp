#pragma once
// Wavefront OBJ: `v x y z` vertices and `f` faces (v, v/vt, v/vt/vn, v//vn; negative = relative to the vertices read so
// far; polygons fan-triangulated). Everything else (vt, vn, groups, materials) is ignored: the twin needs geometry only.
#include <string>

#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

// Coordinates as stored. Throws InputError "<path>:<line>: <reason>" for a malformed or out-of-range line.
Mesh read_obj(const std::string& path);

}  // namespace twinslam::twin
