#include "twinslam/sim/world/ply.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "twinslam/core/error.hpp"

namespace twinslam::sim {
namespace {

template <typename T>
void put(std::ostream& out, T value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));  // x86-64 is little-endian, as the header says
}

template <typename T>
T get(std::istream& in, const std::string& path) {
  T value;
  if (!in.read(reinterpret_cast<char*>(&value), sizeof(T))) throw InputError(where(path, 0, "PLY body is truncated"));
  return value;
}

struct Header {
  std::size_t vertices = 0, faces = 0;
  bool vertex_double = true;
  bool has_building = false, has_kind = false;
  Origin origin;
  bool has_origin = false;
};

Header read_header(std::istream& in, const std::string& path) {
  Header h;
  std::string line;
  std::size_t n = 0;
  std::string element;
  int vertex_props = 0;
  auto fail = [&](const std::string& what) { return InputError(where(path, n, what)); };
  if (!std::getline(in, line) || line != "ply") throw fail("not a PLY file (first line is not 'ply')");
  n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ss(line);
    std::string word;
    ss >> word;
    if (word == "end_header") {
      if (vertex_props != 3) throw fail("vertex element needs exactly the properties x y z");
      return h;
    }
    if (word == "format") {
      std::string fmt;
      ss >> fmt;
      if (fmt != "binary_little_endian") throw fail("only binary_little_endian PLY is supported, got '" + fmt + "'");
    } else if (word == "comment") {
      std::string key;
      ss >> key;
      if (key == "twinslam_origin") {
        if (!(ss >> h.origin.lat_deg >> h.origin.lon_deg >> h.origin.alt_m)) throw fail("malformed twinslam_origin");
        h.has_origin = true;
      }
    } else if (word == "element") {
      std::size_t count = 0;
      ss >> element >> count;
      if (element == "vertex") h.vertices = count;
      else if (element == "face") h.faces = count;
      else throw fail("unsupported element '" + element + "'");
    } else if (word == "property") {
      std::string type, name;
      ss >> type;
      if (element == "vertex") {
        ss >> name;
        if (type != "double" && type != "float" && type != "float64" && type != "float32")
          throw fail("vertex property '" + name + "' must be float or double");
        h.vertex_double = (type == "double" || type == "float64");
        const char* expected[] = {"x", "y", "z"};
        if (vertex_props >= 3 || name != expected[vertex_props]) throw fail("vertex properties must be x y z");
        ++vertex_props;
      } else if (element == "face") {
        if (type == "list") {
          std::string count_type, index_type;
          ss >> count_type >> index_type >> name;
          if ((count_type != "uchar" && count_type != "uint8") ||
              (index_type != "int" && index_type != "uint" && index_type != "int32" && index_type != "uint32"))
            throw fail("face list must be 'list uchar int'");
        } else {
          ss >> name;
          if (name == "building_id" && (type == "int" || type == "int32")) h.has_building = true;
          else if (name == "kind" && (type == "uchar" || type == "uint8")) h.has_kind = true;
          else throw fail("unsupported face property '" + type + " " + name + "'");
        }
      }
    } else if (word != "obj_info") {
      throw fail("unexpected header line '" + line + "'");
    }
  }
  throw fail("PLY header has no end_header");
}

}  // namespace

void write_ply(const std::string& path, const TriMesh& mesh, const Origin& origin) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(where(path, 0, "cannot open PLY file for writing"));
  std::ostringstream header;
  header << std::setprecision(std::numeric_limits<double>::max_digits10);
  header << "ply\nformat binary_little_endian 1.0\n"
         << "comment twinslam mesh; W = East-North-Up [m] at the origin below (WGS84 lat lon [deg], alt [m])\n"
         << "comment twinslam_origin " << origin.lat_deg << ' ' << origin.lon_deg << ' ' << origin.alt_m << '\n'
         << "comment kind: 0 ground, 1 facade, 2 roof, 3 detail\n"
         << "element vertex " << mesh.p_W.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
         << "element face " << mesh.triangles.size()
         << "\nproperty list uchar int vertex_indices\nproperty int building_id\nproperty uchar kind\nend_header\n";
  out << header.str();
  for (const auto& p : mesh.p_W) {
    put(out, p.x());
    put(out, p.y());
    put(out, p.z());
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    put<std::uint8_t>(out, 3);
    for (int k = 0; k < 3; ++k) put<std::int32_t>(out, mesh.triangles[i][k]);
    put<std::int32_t>(out, mesh.building_id[i]);
    put<std::uint8_t>(out, static_cast<std::uint8_t>(mesh.kind[i]));
  }
  if (!out) throw InputError(where(path, 0, "write failed"));
}

PlyMesh read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where(path, 0, "cannot open PLY file"));
  const Header h = read_header(in, path);
  PlyMesh result;
  result.origin = h.origin;
  result.has_origin = h.has_origin;
  TriMesh& m = result.mesh;
  m.p_W.reserve(h.vertices);
  for (std::size_t i = 0; i < h.vertices; ++i) {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = h.vertex_double ? get<double>(in, path) : get<float>(in, path);
    m.p_W.push_back(p);
  }
  for (std::size_t i = 0; i < h.faces; ++i) {
    if (get<std::uint8_t>(in, path) != 3) throw InputError(where(path, 0, "face " + std::to_string(i) + " is not a triangle"));
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      t[k] = get<std::int32_t>(in, path);
      if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= h.vertices)
        throw InputError(where(path, 0, "face " + std::to_string(i) + " has a vertex index out of range"));
    }
    m.triangles.push_back(t);
    m.building_id.push_back(h.has_building ? get<std::int32_t>(in, path) : kNoBuilding);
    const std::uint8_t kind = h.has_kind ? get<std::uint8_t>(in, path) : 1;
    if (kind > 3) throw InputError(where(path, 0, "face " + std::to_string(i) + " has an unknown kind"));
    m.kind.push_back(static_cast<SurfaceKind>(kind));
  }
  return result;
}

}  // namespace twinslam::sim
