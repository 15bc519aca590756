// A real city file -> its triangles in W, each labelled with the part (building, structure, terrain) it belongs to.
// The geometry comes from the twin loaders (common/twin); only the labelling is done here.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "real_city_parts.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/cityjson.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/osm.hpp"
#include "twinslam/twin/tiles3d.hpp"

namespace twinslam::sim::detail {
namespace {

// CityJSON object types (1.0-2.0) that are buildings; BuildingParts and the like are joined to their Building.
const std::set<std::string> kBuildingTypes = {"Building",          "BuildingPart",    "BuildingInstallation",
                                              "BuildingConstructiveElement",        "BuildingFurniture",
                                              "BuildingRoom",      "BuildingStorey",  "BuildingUnit"};
// Types that are the ground: surfaces the drone flies over, textured as paving.
const std::set<std::string> kTerrainTypes = {"TINRelief", "Road",      "Railway",   "TransportSquare",
                                             "Waterway",  "LandUse",   "PlantCover", "WaterBody"};

// The building an object belongs to: its topmost parent among the file's objects (a BuildingPart's Building).
std::string root_building(const std::string& id, const std::map<std::string, std::string>& parent_of) {
  std::string root = id;
  for (int depth = 0; depth < 8; ++depth) {  // CityJSON nests parts a level or two; a cycle ends here
    const auto it = parent_of.find(root);
    if (it == parent_of.end()) break;
    root = it->second;
  }
  return root;
}

SourceModel from_cityjson(twin::CityJsonModel model) {
  SourceModel out;
  std::map<std::string, std::string> parent_of;
  for (const twin::CityObjectInfo& o : model.objects)
    if (!o.parents.empty()) parent_of[o.id] = o.parents.front();
  out.part_of_triangle.assign(model.mesh_W.num_triangles(), -1);
  for (const twin::CityObjectInfo& o : model.objects) {
    SourcePart part;
    if (kBuildingTypes.count(o.type)) part.building = root_building(o.id, parent_of);
    else part.role = kTerrainTypes.count(o.type) ? PartRole::kTerrain : PartRole::kStructure;
    const int index = static_cast<int>(out.parts.size());
    out.parts.push_back(part);
    for (std::size_t t = o.first_triangle; t < o.first_triangle + o.num_triangles; ++t) out.part_of_triangle[t] = index;
  }
  out.mesh = std::move(model.mesh_W);
  return out;
}

SourceModel from_osm(twin::OsmModel model) {
  SourceModel out;
  std::vector<int> part_of_vertex(model.mesh_W.num_vertices(), -1);
  for (const twin::OsmBuildingInfo& b : model.buildings) {
    const int index = static_cast<int>(out.parts.size());
    out.parts.push_back({PartRole::kBuilding, std::string(b.relation ? "osm relation " : "osm way ") +
                                                  std::to_string(b.osm_id)});
    for (std::size_t v = b.first_vertex; v < b.first_vertex + b.num_vertices; ++v) part_of_vertex[v] = index;
  }
  for (const Eigen::Vector3i& t : model.mesh_W.triangles) out.part_of_triangle.push_back(part_of_vertex[t[0]]);
  out.mesh = std::move(model.mesh_W);
  return out;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
};

Eigen::AlignedBox2d plan(const Eigen::AlignedBox3d& b, double grow) {  // the box seen from above, grown [m]
  const Eigen::Vector2d g = Eigen::Vector2d::Constant(grow);
  return {Eigen::Vector2d(b.min().head<2>() - g), Eigen::Vector2d(b.max().head<2>() + g)};
}

// Connected components over vertices closer than weld_m (exporters duplicate vertices per face) and shared triangles;
// returns each component's bounds by root vertex.
std::map<int, Eigen::AlignedBox3d> connect(const twin::Mesh& mesh, double weld_m, UnionFind* uf) {
  std::map<std::tuple<long long, long long, long long>, int> welded;
  for (std::size_t i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d q = mesh.p_W[i] / weld_m;
    const auto key = std::make_tuple(std::llround(q.x()), std::llround(q.y()), std::llround(q.z()));
    const auto [it, inserted] = welded.try_emplace(key, static_cast<int>(i));
    if (!inserted) uf->parent[uf->find(static_cast<int>(i))] = uf->find(it->second);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    uf->parent[uf->find(t[1])] = uf->find(t[0]);
    uf->parent[uf->find(t[2])] = uf->find(t[0]);
  }
  std::map<int, Eigen::AlignedBox3d> box;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) box[uf->find(t[0])].extend(mesh.p_W[t[k]]);
  return box;
}

// Components at least 1 m high overlapping in plan are one building (a detailed model's walls, floors, roof and
// windows are often separate meshes, stacked parts with gaps too), in passes until no two overlap; a flat component
// within a building's plan is part of it. Returns the buildings' bounds by root.
std::map<int, Eigen::AlignedBox3d> join_buildings(const std::map<int, Eigen::AlignedBox3d>& box, double weld_m,
                                                  UnionFind* uf) {
  std::map<int, Eigen::AlignedBox3d> building;
  for (const auto& [root, b] : box)
    if (b.sizes().z() >= 1.0) building[root] = b;
  for (bool merged = true; merged;) {
    merged = false;
    for (auto a = building.begin(); a != building.end(); ++a)
      for (auto b = std::next(a); b != building.end();) {
        if (!plan(a->second, weld_m).intersects(plan(b->second, 0))) {
          ++b;
          continue;
        }
        a->second.extend(b->second);
        uf->parent[b->first] = a->first;
        b = building.erase(b);
        merged = true;
      }
  }
  for (const auto& [root, b] : box) {
    if (b.sizes().z() >= 1.0) continue;
    for (const auto& [building_root, bb] : building)
      if (plan(bb, 0.5).contains(plan(b, 0))) {
        uf->parent[root] = building_root;
        break;
      }
  }
  return building;
}

// Mesh and 3D Tiles content carry no building ids: buildings are joined components (join_buildings); flat components
// outside every building are terrain.
SourceModel from_components(twin::Mesh mesh, double weld_m) {
  UnionFind uf(mesh.num_vertices());
  const std::map<int, Eigen::AlignedBox3d> building = join_buildings(connect(mesh, weld_m, &uf), weld_m, &uf);
  std::map<int, int> part_of_root;  // root -> part, numbered in triangle order
  SourceModel out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const int root = uf.find(t[0]);
    const auto [it, inserted] = part_of_root.try_emplace(root, static_cast<int>(out.parts.size()));
    if (inserted) {
      if (building.count(root)) out.parts.push_back({PartRole::kBuilding, "component " + std::to_string(it->second)});
      else out.parts.push_back({PartRole::kTerrain, ""});
    }
    out.part_of_triangle.push_back(it->second);
  }
  out.mesh = std::move(mesh);
  return out;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

SourceModel load_by_source(const CityConfig& city, const twin::LoadOptions& options, const RealCityConfig& config,
                           twin::LoadReport* report) {
  const std::string& path = *city.path;
  if (city.source == "cityjson") return from_cityjson(twin::load_cityjson(path, options, report));
  if (city.source == "osm") return from_osm(twin::load_osm(path, options, report));
  if (city.source == "3dtiles") return from_components(twin::load_3dtiles(path, options, report), config.weld_m);
  const std::string ext = lower_extension(path);
  if (ext != ".ply" && ext != ".obj" && ext != ".glb" && ext != ".gltf")
    throw InputError(path + ": city.source mesh reads .ply .obj .glb .gltf (a CityJSON, OSM or tileset.json file "
                            "needs city.source cityjson, osm or 3dtiles)");
  return from_components(twin::load_twin_source(path, options, report), config.weld_m);
}

}  // namespace

SourceModel load_source_model(const Scenario& scenario, const Origin& origin, const RealCityConfig& config) {
  const CityConfig& city = scenario.city;
  if (!city.path || city.path->empty())
    throw InputError(where(scenario.name, 0, "city.path: required when city.source is " + city.source));
  twin::LoadOptions options;
  options.origin = {origin.lat_deg, origin.lon_deg, origin.alt_m};
  options.crs = city.crs;
  twin::LoadReport report;
  SourceModel model;
  try {
    if (!std::filesystem::is_regular_file(*city.path)) throw InputError(*city.path + ": no such file");
    model = load_by_source(city, options, config, &report);
  } catch (const InputError& e) {
    std::string what = e.what();
    if (what.find("no CRS") != std::string::npos) what += " (in a scenario: city.crs)";
    throw InputError(where(scenario.name, 0, "city.path: " + what));
  }
  model.rejected = std::move(report.rejected);
  model.warnings = std::move(report.warnings);
  return model;
}

}  // namespace twinslam::sim::detail
