// CityJSON loader: file-level checks (JSON, type, version, transform, vertices, CRS) and the vertex conversion into
// W; the per-object geometry lives in cityjson_geometry.cpp.
#include "twinslam/twin/cityjson.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>

#include <nlohmann/json.hpp>

#include "cityjson_geometry.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::twin {
namespace {

using nlohmann::json;

Eigen::Vector3d vec3(const json& j, const std::string& path, const std::string& what) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw InputError(where(path, 0, what + " must be an array of 3 numbers"));
  const Eigen::Vector3d v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  if (!v.allFinite()) throw InputError(where(path, 0, what + " is not finite"));
  return v;
}

// The CRS string of metadata.referenceSystem (1.0: "urn:ogc:def:crs:EPSG::7415"; 1.1 / 2.0: an OGC URL), or "".
std::string file_crs(const json& doc) {
  const auto meta = doc.find("metadata");
  if (meta == doc.end() || !meta->is_object()) return "";
  const auto rs = meta->find("referenceSystem");
  if (rs == meta->end() || !rs->is_string()) return "";
  return rs->get<std::string>();
}

}  // namespace

CityJsonModel load_cityjson(const std::string& path, const LoadOptions& options, LoadReport* report) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where(path, 0, "cannot open CityJSON file"));
  json doc;
  try {
    doc = json::parse(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const json::exception& e) {  // syntax, and out_of_range for numbers like 1E434 (found by fuzzing)
    throw InputError(where(path, 0, std::string("JSON syntax error: ") + e.what()));
  }
  if (!doc.is_object() || doc.value("type", json()) != "CityJSON")
    throw InputError(where(path, 0, "not a CityJSON file (no \"type\": \"CityJSON\")"));
  const json version = doc.value("version", json());
  const std::string ver = version.is_string() ? version.get<std::string>() : "";
  if (ver != "1.0" && ver != "1.1" && ver != "2.0" && ver.rfind("1.0.", 0) != 0 && ver.rfind("1.1.", 0) != 0 &&
      ver.rfind("2.0.", 0) != 0)
    throw InputError(where(path, 0, "unsupported CityJSON version '" + ver + "' (1.0, 1.1, 2.0 are)"));

  Eigen::Vector3d scale = Eigen::Vector3d::Ones(), translate = Eigen::Vector3d::Zero();
  if (const auto t = doc.find("transform"); t != doc.end()) {
    if (!t->is_object() || !t->contains("scale") || !t->contains("translate"))
      throw InputError(where(path, 0, "transform needs scale and translate"));
    scale = vec3((*t)["scale"], path, "transform.scale");
    translate = vec3((*t)["translate"], path, "transform.translate");
  } else if (ver != "1.0" && ver.rfind("1.0.", 0) != 0) {
    throw InputError(where(path, 0, "CityJSON " + ver + " requires a transform"));
  }
  const auto vertices = doc.find("vertices");
  if (vertices == doc.end() || !vertices->is_array()) throw InputError(where(path, 0, "no vertices array"));
  if (vertices->size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw InputError(where(path, 0, "more vertices than a mesh can index"));
  const auto objects = doc.find("CityObjects");
  if (objects == doc.end() || !objects->is_object()) throw InputError(where(path, 0, "no CityObjects object"));

  CityJsonModel model;
  model.crs = file_crs(doc);
  if (model.crs.empty() && options.crs) model.crs = *options.crs;
  if (model.crs.empty())
    throw InputError(where(path, 0, "no CRS: metadata.referenceSystem is missing, give one (--crs EPSG:nnnn)"));
  std::vector<Eigen::Vector3d> p_W;
  p_W.reserve(vertices->size());
  try {
    const CrsTransform crs(model.crs);
    const EnuFrame frame(options.origin);
    for (std::size_t i = 0; i < vertices->size(); ++i) {
      const Eigen::Vector3d v = vec3((*vertices)[i], path, "vertex " + std::to_string(i));
      const Eigen::Vector3d lla = crs.to_lla(v.cwiseProduct(scale) + translate);
      p_W.push_back(frame.from_lla(lla.x(), lla.y(), lla.z()));
    }
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind(path, 0) == 0 ? what : where(path, 0, what));
  }

  LoadReport local;
  LoadReport& rep = report != nullptr ? *report : local;
  std::vector<int> used(p_W.size(), -1);  // compaction: file vertex -> mesh vertex
  for (const auto& [id, object] : objects->items()) {
    CityObjectInfo info;
    info.id = id;
    std::vector<Eigen::Vector3i> triangles;  // file vertex indices
    std::string problem;
    if (!object.is_object()) {
      problem = "not a JSON object";
    } else {
      info.type = object.value("type", std::string());
      if (const auto parents = object.find("parents"); parents != object.end() && parents->is_array())
        for (const json& parent : *parents)
          if (parent.is_string()) info.parents.push_back(parent.get<std::string>());
      const auto geometry = object.find("geometry");
      if (geometry == object.end() || (geometry->is_array() && geometry->empty())) continue;  // e.g. a parent
      problem = triangulate_city_object(*geometry, p_W, info.lod, triangles, rep, where(path, 0, "CityObject '" + id + "'"));
    }
    if (!problem.empty()) {
      rep.rejected.push_back(where(path, 0, "CityObject '" + id + "': " + problem));
      continue;
    }
    if (triangles.empty()) continue;
    info.first_triangle = model.mesh_W.triangles.size();
    info.num_triangles = triangles.size();
    for (Eigen::Vector3i t : triangles) {
      for (int k = 0; k < 3; ++k) {
        int& slot = used[static_cast<std::size_t>(t[k])];
        if (slot < 0) {
          slot = static_cast<int>(model.mesh_W.p_W.size());
          model.mesh_W.p_W.push_back(p_W[static_cast<std::size_t>(t[k])]);
        }
        t[k] = slot;
      }
      model.mesh_W.triangles.push_back(t);
    }
    model.objects.push_back(info);
    ++rep.parts_loaded;
  }
  return model;
}

}  // namespace twinslam::twin
