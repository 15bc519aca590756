// CityJSON boundaries: a surface is [outer ring, hole rings...], a ring is [vertex indices]. MultiSurface and
// CompositeSurface hold surfaces, a Solid holds shells (outer, then inner) of surfaces, Multi/CompositeSolid solids.
#include "cityjson_geometry.hpp"

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "twinslam/twin/polygon_triangulation.hpp"

namespace twinslam::twin {
namespace {

using nlohmann::json;
using Surface = std::vector<std::vector<int>>;

// Array levels above the surfaces for each geometry type; -1 = no surfaces (points, lines, templates).
int surface_depth(const std::string& type) {
  if (type == "MultiSurface" || type == "CompositeSurface") return 0;
  if (type == "Solid") return 1;
  if (type == "MultiSolid" || type == "CompositeSolid") return 2;
  return -1;
}

// LoD as written (1.0: a number such as 2 or 2.2; 1.1 / 2.0: a string such as "2.2") and its numeric value.
bool read_lod(const json& g, std::string& text, double& value) {
  const auto it = g.find("lod");
  if (it == g.end()) return false;
  if (it->is_string()) text = it->get<std::string>();
  else if (it->is_number()) text = it->dump();
  else return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end != text.c_str();
}

// Appends the surfaces under `b` (depth array levels above them); returns "" or the problem.
std::string collect(const json& b, int depth, std::size_t num_vertices, std::vector<Surface>& out) {
  if (!b.is_array()) return "boundaries nesting does not match the geometry type";
  if (depth > 0) {
    for (const json& child : b)
      if (std::string e = collect(child, depth - 1, num_vertices, out); !e.empty()) return e;
    return "";
  }
  for (const json& surface : b) {
    if (!surface.is_array()) return "boundaries nesting does not match the geometry type (surface)";
    Surface s;
    for (const json& ring : surface) {
      if (!ring.is_array()) return "boundaries nesting does not match the geometry type (ring)";
      std::vector<int> r;
      r.reserve(ring.size());
      for (const json& idx : ring) {
        if (!idx.is_number_integer()) return "ring holds a non-integer vertex index";
        const long long v = idx.get<long long>();
        if (v < 0 || static_cast<unsigned long long>(v) >= num_vertices)
          return "vertex index " + std::to_string(v) + " out of range (" + std::to_string(num_vertices) + " vertices)";
        r.push_back(static_cast<int>(v));
      }
      s.push_back(std::move(r));
    }
    out.push_back(std::move(s));
  }
  return "";
}

}  // namespace

std::string triangulate_city_object(const json& geometry, const std::vector<Eigen::Vector3d>& p_W,
                                    std::string& lod_used, std::vector<Eigen::Vector3i>& triangles, LoadReport& report,
                                    const std::string& context) {
  if (!geometry.is_array()) return "geometry is not an array";
  double best = -1.0;
  for (const json& g : geometry) {
    if (!g.is_object() || !g.contains("type") || !g["type"].is_string()) return "geometry without a type";
    const std::string type = g["type"].get<std::string>();
    std::string text;
    double lod = 0.0;
    if (surface_depth(type) < 0) {
      report.rejected.push_back(context + ": skipped " + type + " geometry (no surfaces)");
      continue;
    }
    if (!read_lod(g, text, lod)) return type + " geometry without a valid lod";
    if (lod > best) best = lod, lod_used = text;
  }
  for (const json& g : geometry) {
    const std::string type = g["type"].get<std::string>();
    std::string text;
    double lod = 0.0;
    if (surface_depth(type) < 0 || !read_lod(g, text, lod) || lod != best) continue;
    if (!g.contains("boundaries")) return type + " geometry without boundaries";
    std::vector<Surface> surfaces;
    if (std::string e = collect(g["boundaries"], surface_depth(type), p_W.size(), surfaces); !e.empty())
      return type + ": " + e;
    for (const Surface& s : surfaces) {
      const auto tris = triangulate_polygon(p_W, s);
      triangles.insert(triangles.end(), tris.begin(), tris.end());
    }
  }
  return "";
}

}  // namespace twinslam::twin
