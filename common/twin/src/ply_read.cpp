// PLY reader: the header is parsed into elements and typed properties; the body is read from memory through one
// cursor that checks every byte it takes (binary) or every token (ascii), so a truncated or lying file is an
// InputError, never an out-of-bounds read or a huge allocation.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/ply.hpp"

namespace twinslam::twin {
namespace {

enum class Type { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64 };

std::optional<Type> parse_type(const std::string& s) {
  if (s == "char" || s == "int8") return Type::kI8;
  if (s == "uchar" || s == "uint8") return Type::kU8;
  if (s == "short" || s == "int16") return Type::kI16;
  if (s == "ushort" || s == "uint16") return Type::kU16;
  if (s == "int" || s == "int32") return Type::kI32;
  if (s == "uint" || s == "uint32") return Type::kU32;
  if (s == "float" || s == "float32") return Type::kF32;
  if (s == "double" || s == "float64") return Type::kF64;
  return std::nullopt;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::kI8: case Type::kU8: return 1;
    case Type::kI16: case Type::kU16: return 2;
    case Type::kI32: case Type::kU32: case Type::kF32: return 4;
    case Type::kF64: return 8;
  }
  return 1;
}

struct Property {
  std::string name;
  Type type = Type::kF32;
  bool is_list = false;
  Type count_type = Type::kU8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> props;
};

struct Header {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<Element> elements;
  std::optional<GeoOrigin> origin;
  std::size_t body_offset = 0;  // bytes
};

Header parse_header(const std::string& data, const std::string& path) {
  Header h;
  std::size_t pos = 0, line_no = 0;
  bool have_format = false;
  auto fail = [&](const std::string& what) { return InputError(where(path, line_no, what)); };
  while (true) {
    const std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) throw fail("PLY header has no end_header");
    std::string line = data.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1) {
      if (line != "ply") throw fail("not a PLY file (first line is not 'ply')");
      continue;
    }
    std::istringstream ss(line);
    std::string word;
    ss >> word;
    if (word == "end_header") break;
    if (word == "format") {
      std::string fmt;
      ss >> fmt;
      if (fmt == "ascii") h.format = PlyFormat::kAscii;
      else if (fmt == "binary_little_endian") h.format = PlyFormat::kBinaryLittleEndian;
      else if (fmt == "binary_big_endian") h.format = PlyFormat::kBinaryBigEndian;
      else throw fail("unknown PLY format '" + fmt + "'");
      have_format = true;
    } else if (word == "comment") {
      std::string key;
      ss >> key;
      if (key == "twinslam_origin") {
        GeoOrigin o;
        if (!(ss >> o.lat_deg >> o.lon_deg >> o.alt_m)) throw fail("malformed twinslam_origin comment");
        h.origin = o;
      }
    } else if (word == "element") {
      Element e;
      long long count = -1;
      if (!(ss >> e.name >> count) || count < 0) throw fail("malformed element line '" + line + "'");
      e.count = static_cast<std::size_t>(count);
      h.elements.push_back(e);
    } else if (word == "property") {
      if (h.elements.empty()) throw fail("property before any element");
      Property p;
      std::string type;
      ss >> type;
      if (type == "list") {
        std::string count_type, item_type;
        ss >> count_type >> item_type >> p.name;
        const auto ct = parse_type(count_type), it = parse_type(item_type);
        if (!ct || !it || *ct == Type::kF32 || *ct == Type::kF64)
          throw fail("bad list property '" + line + "'");
        p.is_list = true;
        p.count_type = *ct;
        p.type = *it;
      } else {
        const auto t = parse_type(type);
        if (!t) throw fail("unknown property type '" + type + "'");
        p.type = *t;
        ss >> p.name;
      }
      if (p.name.empty()) throw fail("property without a name");
      h.elements.back().props.push_back(p);
    } else if (word != "obj_info" && !word.empty()) {
      throw fail("unexpected header line '" + line + "'");
    }
  }
  if (!have_format) throw fail("PLY header has no format line");
  h.body_offset = pos;
  return h;
}

// Reads typed values from the body, ascii or binary, with bounds checks.
class Cursor {
 public:
  Cursor(const std::string& data, std::size_t pos, PlyFormat format, const std::string& path)
      : data_(data), pos_(pos), format_(format), path_(path) {}

  double read(Type t) {
    if (format_ == PlyFormat::kAscii) return read_token();
    const std::size_t n = type_size(t);
    if (data_.size() - pos_ < n) throw InputError(where(path_, 0, "PLY body is truncated"));
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, n);
    pos_ += n;
    const bool swap = (format_ == PlyFormat::kBinaryBigEndian) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(b, b + n);
    switch (t) {
      case Type::kI8: return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case Type::kU8: return static_cast<double>(b[0]);
      case Type::kI16: return as<std::int16_t>(b);
      case Type::kU16: return as<std::uint16_t>(b);
      case Type::kI32: return as<std::int32_t>(b);
      case Type::kU32: return as<std::uint32_t>(b);
      case Type::kF32: return as<float>(b);
      case Type::kF64: return as<double>(b);
    }
    return 0.0;
  }
  std::size_t remaining() const { return data_.size() - pos_; }

 private:
  template <typename T>
  static double as(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<double>(v);
  }
  double read_token() {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (pos_ >= data_.size()) throw InputError(where(path_, 0, "PLY body is truncated"));
    std::size_t end = pos_;
    while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
    const std::string token = data_.substr(pos_, end - pos_);
    pos_ = end;
    char* stop = nullptr;
    const double v = std::strtod(token.c_str(), &stop);
    if (stop == token.c_str() || *stop != '\0')
      throw InputError(where(path_, 0, "PLY body has a non-number '" + token + "'"));
    return v;
  }
  const std::string& data_;
  std::size_t pos_;
  PlyFormat format_;
  const std::string& path_;
};

int find_prop(const Element& e, const std::string& name) {
  for (std::size_t i = 0; i < e.props.size(); ++i)
    if (e.props[i].name == name && !e.props[i].is_list) return static_cast<int>(i);
  return -1;
}

}  // namespace

PlyFile read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where(path, 0, "cannot open PLY file"));
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Header h = parse_header(data, path);
  PlyFile out;
  out.origin = h.origin;
  Cursor cur(data, h.body_offset, h.format, path);
  std::size_t vertices_seen = 0;
  std::vector<std::vector<long long>> polygons;
  for (const Element& e : h.elements) {
    // Every item takes at least one byte (binary) or two characters (ascii): a larger count is a lie.
    if (e.count > cur.remaining()) throw InputError(where(path, 0, "PLY body is truncated (" + e.name + ")"));
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, ilist = -1;
    if (is_vertex) {
      ix = find_prop(e, "x"), iy = find_prop(e, "y"), iz = find_prop(e, "z");
      inx = find_prop(e, "nx"), iny = find_prop(e, "ny"), inz = find_prop(e, "nz");
      if (ix < 0 || iy < 0 || iz < 0) throw InputError(where(path, 0, "PLY vertex element lacks x, y or z"));
      if (e.count > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InputError(where(path, 0, "PLY has more vertices than a mesh can index"));
      vertices_seen = e.count;
      out.mesh.p_W.reserve(e.count);
    }
    const bool normals = is_vertex && inx >= 0 && iny >= 0 && inz >= 0;
    if (is_face) {
      for (std::size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].is_list && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
          ilist = static_cast<int>(i);
      if (ilist < 0) throw InputError(where(path, 0, "PLY face element has no vertex_indices list"));
    }
    std::vector<double> values(e.props.size());
    for (std::size_t item = 0; item < e.count; ++item) {
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (!p.is_list) {
          values[k] = cur.read(p.type);
          continue;
        }
        const double n = cur.read(p.count_type);
        if (n < 0 || n > static_cast<double>(cur.remaining()))
          throw InputError(where(path, 0, "PLY list length " + std::to_string(n) + " is impossible"));
        std::vector<long long> list(static_cast<std::size_t>(n));
        for (auto& v : list) {
          const double index = cur.read(p.type);
          // A float list value beyond long long is undefined to convert (found by fuzzing); any index that large is
          // out of range anyway.
          if (!(std::abs(index) < 9.0e18)) throw InputError(where(path, 0, "PLY list value out of range"));
          v = static_cast<long long>(index);
        }
        if (static_cast<int>(k) == ilist) polygons.push_back(std::move(list));
      }
      if (is_vertex) {
        const Eigen::Vector3d p(values[ix], values[iy], values[iz]);
        if (!p.allFinite())
          throw InputError(where(path, 0, "PLY vertex " + std::to_string(item) + " has a non-finite coordinate"));
        out.mesh.p_W.push_back(p);
        if (normals) out.mesh.n_W.emplace_back(values[inx], values[iny], values[inz]);
      }
    }
  }
  for (Eigen::Vector3d& n : out.mesh.n_W) {
    const double len = n.norm();
    n = (std::isfinite(len) && len > 0.0) ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  }
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    for (long long v : poly)
      if (v < 0 || static_cast<std::size_t>(v) >= vertices_seen)
        throw InputError(where(path, 0, "PLY face " + std::to_string(f) + " has vertex index " + std::to_string(v) +
                                            " out of range (" + std::to_string(vertices_seen) + " vertices)"));
    for (std::size_t k = 2; k < poly.size(); ++k)  // fan: (0, k-1, k); faces with < 3 vertices give nothing
      out.mesh.triangles.emplace_back(static_cast<int>(poly[0]), static_cast<int>(poly[k - 1]),
                                      static_cast<int>(poly[k]));
  }
  return out;
}

}  // namespace twinslam::twin
