// OSM buildings: footprints (ways, multipolygon rings) -> heights from tags -> extruded blocks in W.
#include "twinslam/twin/osm.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "osm_read.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/polygon_triangulation.hpp"

namespace twinslam::twin {
namespace {

using Ring = std::vector<std::int64_t>;  // node ids, closed (first == last)

std::string tag(const std::map<std::string, std::string>& tags, const std::string& key) {
  const auto it = tags.find(key);
  return it == tags.end() ? "" : it->second;
}

// Joins way pieces into closed rings (a multipolygon's outer or inner members may be split into several ways).
bool join_rings(std::vector<Ring> pieces, std::vector<Ring>& rings) {
  while (!pieces.empty()) {
    Ring ring = std::move(pieces.back());
    pieces.pop_back();
    if (ring.empty()) continue;
    while (ring.size() < 2 || ring.front() != ring.back()) {
      bool extended = false;
      for (std::size_t i = 0; i < pieces.size() && !extended; ++i) {
        Ring& p = pieces[i];
        if (p.empty()) continue;
        if (p.front() == ring.back()) ring.insert(ring.end(), p.begin() + 1, p.end());
        else if (p.back() == ring.back()) ring.insert(ring.end(), p.rbegin() + 1, p.rend());
        else continue;
        pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(i));
        extended = true;
      }
      if (!extended) return false;
    }
    rings.push_back(std::move(ring));
  }
  return true;
}

struct Footprint {
  std::vector<std::vector<Eigen::Vector2d>> rings;  // [0] outer, then holes; open (no repeated closing point)
};

double signed_area(const std::vector<Eigen::Vector2d>& r) {
  double s = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Eigen::Vector2d& a = r[i];
    const Eigen::Vector2d& b = r[(i + 1) % r.size()];
    s += a.x() * b.y() - b.x() * a.y();
  }
  return s / 2.0;
}

// Node ids -> east / north in W; "" or the problem.
std::string to_footprint(const std::vector<Ring>& rings, const OsmData& data, const EnuFrame& frame, Footprint& fp) {
  for (std::size_t k = 0; k < rings.size(); ++k) {
    const Ring& ring = rings[k];
    if (ring.size() < 4 || ring.front() != ring.back()) return "footprint is not a closed ring of >= 3 nodes";
    std::vector<Eigen::Vector2d> xy;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
      const auto node = data.nodes.find(ring[i]);
      if (node == data.nodes.end()) return "node " + std::to_string(ring[i]) + " is missing";
      const Eigen::Vector2d p =
          frame.from_lla(node->second.lat_deg, node->second.lon_deg, frame.origin().alt_m).head<2>();
      if (xy.empty() || (p - xy.back()).norm() > 1e-6) xy.push_back(p);
    }
    while (xy.size() > 1 && (xy.front() - xy.back()).norm() <= 1e-6) xy.pop_back();
    const double area = signed_area(xy);
    if (xy.size() < 3 || std::abs(area) < 1e-6) return "footprint has zero area";
    // Outer ring counter-clockwise seen from above, holes clockwise: then every wall faces out of the building.
    if ((k == 0) != (area > 0)) std::reverse(xy.begin(), xy.end());
    fp.rings.push_back(std::move(xy));
  }
  return "";
}

void extrude(const Footprint& fp, double base, double top, Mesh& mesh) {
  std::vector<std::vector<int>> bottom_rings, top_rings;
  for (const auto& ring : fp.rings) {
    std::vector<int> b, t;
    for (const Eigen::Vector2d& p : ring) {
      b.push_back(static_cast<int>(mesh.p_W.size()));
      mesh.p_W.emplace_back(p.x(), p.y(), base);
      t.push_back(static_cast<int>(mesh.p_W.size()));
      mesh.p_W.emplace_back(p.x(), p.y(), top);
    }
    for (std::size_t i = 0; i < ring.size(); ++i) {  // edge i -> j, building on its left: the wall faces right
      const std::size_t j = (i + 1) % ring.size();
      mesh.triangles.emplace_back(b[i], b[j], t[j]);
      mesh.triangles.emplace_back(b[i], t[j], t[i]);
    }
    bottom_rings.push_back(std::move(b));
    top_rings.push_back(std::move(t));
  }
  for (const Eigen::Vector3i& tri : triangulate_polygon(mesh.p_W, top_rings)) mesh.triangles.push_back(tri);
  if (base > 0.0)  // lifted part: close it from below, facing down
    for (const Eigen::Vector3i& tri : triangulate_polygon(mesh.p_W, bottom_rings))
      mesh.triangles.emplace_back(tri[0], tri[2], tri[1]);
}

// Base and top [m] from the tags (osm.hpp); "" or the problem.
std::string heights(const std::map<std::string, std::string>& tags, const LoadOptions& o, double& base, double& top) {
  double levels = 0.0;
  auto number = [](const std::string& s, double& v) {
    char* end = nullptr;
    v = std::strtod(s.c_str(), &end);
    return !s.empty() && end != s.c_str() && std::isfinite(v) && v >= 0.0;
  };
  if (!parse_osm_height(tag(tags, "height"), &top)) {
    if (number(tag(tags, "building:levels"), levels) && levels > 0) top = levels * o.storey_height_m;
    else top = o.default_height_m;
  }
  base = 0.0;
  if (!parse_osm_height(tag(tags, "min_height"), &base) && number(tag(tags, "building:min_level"), levels))
    base = levels * o.storey_height_m;
  if (!(top > base)) return "base " + std::to_string(base) + " m is not below the top " + std::to_string(top) + " m";
  return "";
}

}  // namespace

bool parse_osm_height(const std::string& text, double* metres) {
  const char* s = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || !std::isfinite(v) || v < 0.0) return false;
  std::string unit(end);
  unit.erase(std::remove_if(unit.begin(), unit.end(), [](unsigned char c) { return std::isspace(c); }), unit.end());
  if (unit.empty() || unit == "m") *metres = v;
  else if (unit == "ft" || unit == "'") *metres = v * 0.3048;
  else return false;
  return true;
}

OsmModel load_osm(const std::string& path, const LoadOptions& options, LoadReport* report) {
  const OsmData data = read_osm_xml(path);
  LoadReport local;
  LoadReport& rep = report != nullptr ? *report : local;
  const EnuFrame frame(options.origin);
  OsmModel model;
  auto add = [&](std::int64_t id, bool relation, const std::vector<Ring>& rings,
                 const std::map<std::string, std::string>& tags) {
    const std::string name = relation ? "relation " + std::to_string(id) : "way " + std::to_string(id);
    Footprint fp;
    OsmBuildingInfo info{id, relation};
    std::string problem = to_footprint(rings, data, frame, fp);
    if (problem.empty()) problem = heights(tags, options, info.base_m, info.top_m);
    if (!problem.empty()) {
      rep.rejected.push_back(where(path, 0, "building " + name + ": " + problem));
      return;
    }
    info.first_vertex = model.mesh_W.p_W.size();
    extrude(fp, info.base_m, info.top_m, model.mesh_W);
    info.num_vertices = model.mesh_W.p_W.size() - info.first_vertex;
    model.buildings.push_back(info);
    ++rep.parts_loaded;
  };
  std::unordered_map<std::int64_t, const OsmWay*> way_by_id;
  for (const OsmWay& w : data.ways) {
    way_by_id[w.id] = &w;
    if (!w.tags.empty()) add(w.id, false, {w.refs}, w.tags);
  }
  for (const OsmRelation& r : data.building_relations) {
    std::vector<Ring> outer_pieces, inner_pieces, outer, inner;
    std::string missing;
    for (const OsmMember& m : r.ways) {
      const auto it = way_by_id.find(m.way);
      if (it == way_by_id.end()) missing = "member way " + std::to_string(m.way) + " is missing";
      else (m.role == "inner" ? inner_pieces : outer_pieces).push_back(it->second->refs);
    }
    if (missing.empty() && (!join_rings(outer_pieces, outer) || !join_rings(inner_pieces, inner)))
      missing = "member ways do not join into closed rings";
    if (missing.empty() && outer.empty()) missing = "no outer ring";
    if (!missing.empty()) {
      rep.rejected.push_back(where(path, 0, "building relation " + std::to_string(r.id) + ": " + missing));
      continue;
    }
    // Each outer ring is one block; every inner ring goes with the outer ring that contains its first node.
    for (const Ring& o : outer) {
      std::vector<Ring> rings{o};
      Footprint probe;
      if (to_footprint({o}, data, frame, probe).empty())
        for (const Ring& in : inner) {
          const auto n = data.nodes.find(in.front());
          if (n == data.nodes.end()) continue;
          const Eigen::Vector2d p = frame.from_lla(n->second.lat_deg, n->second.lon_deg, options.origin.alt_m).head<2>();
          bool inside = false;  // even-odd rule
          const auto& poly = probe.rings[0];
          for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
            if ((poly[i].y() > p.y()) != (poly[j].y() > p.y()) &&
                p.x() < poly[j].x() + (p.y() - poly[j].y()) / (poly[i].y() - poly[j].y()) * (poly[i].x() - poly[j].x()))
              inside = !inside;
          if (inside) rings.push_back(in);
        }
      add(r.id, true, rings, r.tags);
    }
  }
  return model;
}

}  // namespace twinslam::twin
