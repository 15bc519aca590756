// load_twin_source: picks the loader by extension (and, for .json, by content) and brings PLY / OBJ coordinates into W.
#include "twinslam/twin/load.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/cityjson.hpp"
#include "twinslam/twin/gltf.hpp"
#include "twinslam/twin/obj.hpp"
#include "twinslam/twin/osm.hpp"
#include "twinslam/twin/ply.hpp"
#include "twinslam/twin/tiles3d.hpp"

namespace twinslam::twin {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// PLY / OBJ coordinates -> W. With --crs they are in that CRS (through WGS84); a PLY with a twinslam_origin comment is
// in the W of that origin (moved through ECEF when it differs from ours); otherwise they already are in W.
void bring_into_w(Mesh& mesh, const std::optional<GeoOrigin>& file_origin, const LoadOptions& options,
                  const std::string& path) {
  const EnuFrame frame(options.origin);
  if (options.crs) {
    try {
      const CrsTransform crs(*options.crs);
      for (std::size_t i = 0; i < mesh.p_W.size(); ++i) {
        const Eigen::Vector3d p_src = mesh.p_W[i];
        const Eigen::Vector3d lla = crs.to_lla(p_src);
        mesh.p_W[i] = frame.from_lla(lla.x(), lla.y(), lla.z());
        if (i < mesh.n_W.size()) {  // a normal follows the map between the frames: the image of p + 1 m * n
          const Eigen::Vector3d q = crs.to_lla(p_src + mesh.n_W[i]);
          mesh.n_W[i] = (frame.from_lla(q.x(), q.y(), q.z()) - mesh.p_W[i]).normalized();
        }
      }
    } catch (const InputError& e) {
      throw InputError(where(path, 0, e.what()));
    }
    return;
  }
  if (!file_origin) return;
  const GeoOrigin& o = *file_origin;
  const GeoOrigin& w = options.origin;
  if (o.lat_deg == w.lat_deg && o.lon_deg == w.lon_deg && o.alt_m == w.alt_m) return;
  const EnuFrame source(o);
  const Eigen::Matrix3d R_W_S = frame.R_W_ECEF() * source.R_W_ECEF().transpose();
  for (Eigen::Vector3d& p : mesh.p_W) p = frame.from_ecef(source.to_ecef(p));
  for (Eigen::Vector3d& n : mesh.n_W) n = R_W_S * n;
}

enum class Kind { kPly, kObj, kGltf, kTiles, kCityJson, kOsm };

Kind detect(const std::string& path) {
  const std::string name = lower(std::filesystem::path(path).filename().string());
  if (ends_with(name, ".ply")) return Kind::kPly;
  if (ends_with(name, ".obj")) return Kind::kObj;
  if (ends_with(name, ".glb") || ends_with(name, ".gltf")) return Kind::kGltf;
  if (ends_with(name, ".osm")) return Kind::kOsm;
  if (ends_with(name, ".city.json") || ends_with(name, ".cityjson")) return Kind::kCityJson;
  if (ends_with(name, ".json")) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where(path, 0, "cannot open file"));
    // Sniff the whole text: writers sort keys freely (delft.json has "type": "CityJSON" at its very end).
    const std::string head((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (head.find("\"CityJSON\"") != std::string::npos) return Kind::kCityJson;
    if (head.find("\"asset\"") != std::string::npos && head.find("\"root\"") != std::string::npos) return Kind::kTiles;
    throw InputError(where(path, 0, "JSON file is neither CityJSON (\"type\": \"CityJSON\") nor a 3D Tiles tileset "
                                    "(\"asset\" + \"root\")"));
  }
  throw InputError(where(path, 0, "unknown twin source format (expected .ply .obj .glb .gltf tileset.json "
                                  ".json/.city.json (CityJSON) or .osm)"));
}

}  // namespace

Mesh load_twin_source(const std::string& path, const LoadOptions& options, LoadReport* report) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(where(path, 0, "no such file"));
  LoadReport local;
  LoadReport& rep = report != nullptr ? *report : local;
  switch (detect(path)) {
    case Kind::kPly: {
      PlyFile ply = read_ply(path);
      bring_into_w(ply.mesh, ply.origin, options, path);
      rep.parts_loaded += 1;
      return std::move(ply.mesh);
    }
    case Kind::kObj: {
      Mesh mesh = read_obj(path);
      bring_into_w(mesh, std::nullopt, options, path);
      rep.parts_loaded += 1;
      return mesh;
    }
    case Kind::kGltf: {  // a standalone model: y-up model frame turned z-up, then like PLY / OBJ
      Mesh mesh = load_gltf_file(path);
      for (Eigen::Vector3d& p : mesh.p_W) p = gltf_y_up_to_z_up(p);
      for (Eigen::Vector3d& n : mesh.n_W) n = gltf_y_up_to_z_up(n);
      bring_into_w(mesh, std::nullopt, options, path);
      rep.parts_loaded += 1;
      return mesh;
    }
    case Kind::kTiles:
      return load_3dtiles(path, options, &rep);
    case Kind::kCityJson:
      return std::move(load_cityjson(path, options, &rep).mesh_W);
    case Kind::kOsm:
      return std::move(load_osm(path, options, &rep).mesh_W);
  }
  throw InputError(where(path, 0, "unknown twin source format"));
}

}  // namespace twinslam::twin
