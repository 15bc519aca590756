#pragma once
// Private to the CityJSON loader: one city object's "geometry" array -> triangles (file vertex indices).
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

#include "twinslam/twin/load.hpp"

namespace twinslam::twin {

// Triangulates the geometries of the highest LoD. Returns "" on success, else why the object is rejected.
// Geometries without surfaces (points, lines, GeometryInstance) are noted in report.rejected as "<context>: ...".
std::string triangulate_city_object(const nlohmann::json& geometry, const std::vector<Eigen::Vector3d>& p_W,
                                    std::string& lod_used, std::vector<Eigen::Vector3i>& triangles, LoadReport& report,
                                    const std::string& context);

}  // namespace twinslam::twin
