// Wavefront OBJ reader, line by line: only v and f matter for the twin.
#include "twinslam/twin/obj.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "twinslam/core/error.hpp"

namespace twinslam::twin {
namespace {

// The vertex index of one `f` corner ("7", "7/2", "7/2/5", "7//5", "-1"), resolved to 0-based.
int corner_index(const std::string& token, std::size_t vertices, const std::string& path, std::size_t line) {
  const std::string head = token.substr(0, token.find('/'));
  char* end = nullptr;
  const long long v = std::strtoll(head.c_str(), &end, 10);
  if (head.empty() || *end != '\0') throw InputError(where(path, line, "bad face corner '" + token + "'"));
  const long long n = static_cast<long long>(vertices);
  const long long idx = v > 0 ? v - 1 : n + v;  // 1-based, or negative = counted back from the latest vertex
  if (v == 0 || idx < 0 || idx >= n)
    throw InputError(where(path, line, "face index " + head + " out of range (" + std::to_string(n) + " vertices)"));
  return static_cast<int>(idx);
}

}  // namespace

Mesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(where(path, 0, "cannot open OBJ file"));
  Mesh mesh;
  std::string line;
  std::size_t line_no = 0;
  std::vector<int> poly;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ss(line);
    std::string key;
    if (!(ss >> key) || key[0] == '#') continue;
    if (key == "v") {
      Eigen::Vector3d p;
      std::string xs, ys, zs;
      if (!(ss >> xs >> ys >> zs)) throw InputError(where(path, line_no, "vertex needs x y z"));
      const std::string* parts[3] = {&xs, &ys, &zs};
      for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        p[k] = std::strtod(parts[k]->c_str(), &end);
        if (*end != '\0' || !std::isfinite(p[k]))
          throw InputError(where(path, line_no, "vertex coordinate '" + *parts[k] + "' is not a finite number"));
      }
      if (mesh.p_W.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InputError(where(path, line_no, "too many vertices"));
      mesh.p_W.push_back(p);
    } else if (key == "f") {
      poly.clear();
      std::string token;
      while (ss >> token) poly.push_back(corner_index(token, mesh.p_W.size(), path, line_no));
      if (poly.size() < 3) throw InputError(where(path, line_no, "face needs at least 3 vertices"));
      for (std::size_t k = 2; k < poly.size(); ++k) mesh.triangles.emplace_back(poly[0], poly[k - 1], poly[k]);
    }
  }
  return mesh;
}

}  // namespace twinslam::twin
