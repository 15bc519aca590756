// index.json of the twin store: writing, and reading with every key checked (a hand-edited or truncated index must
// give one line naming index.json and the key, never a crash or a silently wrong tile).
#include "store_index.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "twinslam/core/error.hpp"

namespace twinslam::twin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json box_json(const Eigen::AlignedBox3d& b) {
  return json::array({b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z()});
}

// Typed access to the parsed index; every failure names the file and the JSON path of the key.
class Checked {
 public:
  explicit Checked(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void bad(const std::string& path, const std::string& why) const {
    throw InputError(where(file_, 0, "'" + path + "' " + why));
  }
  const json& at(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.is_object()) bad(path, "is not an object");
    const auto it = obj.find(key);
    if (it == obj.end()) bad(join(path, key), "is missing");
    return *it;
  }
  double number(const json& obj, const std::string& key, const std::string& path) const {
    const json& v = at(obj, key, path);
    if (!v.is_number() || !std::isfinite(v.get<double>())) bad(join(path, key), "must be a finite number");
    return v.get<double>();
  }
  long long integer(const json& obj, const std::string& key, const std::string& path) const {
    const json& v = at(obj, key, path);
    if (!v.is_number_integer()) bad(join(path, key), "must be an integer");
    return v.get<long long>();
  }
  std::size_t count(const json& obj, const std::string& key, const std::string& path) const {
    const long long v = integer(obj, key, path);
    if (v < 0) bad(join(path, key), "must not be negative");
    return static_cast<std::size_t>(v);
  }
  std::string string(const json& obj, const std::string& key, const std::string& path) const {
    const json& v = at(obj, key, path);
    if (!v.is_string()) bad(join(path, key), "must be a string");
    return v.get<std::string>();
  }
  std::vector<double> numbers(const json& obj, const std::string& key, const std::string& path, std::size_t n) const {
    const json& v = at(obj, key, path);
    const std::string p = join(path, key);
    if (!v.is_array() || v.size() != n) bad(p, "must be an array of " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const json& x : v) {
      if (!x.is_number() || !std::isfinite(x.get<double>())) bad(p, "must hold finite numbers only");
      out.push_back(x.get<double>());
    }
    return out;
  }
  Eigen::AlignedBox3d box(const json& obj, const std::string& key, const std::string& path) const {
    const std::vector<double> v = numbers(obj, key, path, 6);
    const Eigen::Vector3d lo(v[0], v[1], v[2]), hi(v[3], v[4], v[5]);
    if ((lo.array() > hi.array()).any()) bad(join(path, key), "has a minimum above its maximum");
    return {lo, hi};
  }
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  std::string file_;
};

TileInfo read_tile(const Checked& c, const json& t, const std::string& path) {
  TileInfo info;
  const long long ix = c.integer(t, "ix", path), iy = c.integer(t, "iy", path);
  if (std::llabs(ix) > 100000000 || std::llabs(iy) > 100000000) c.bad(path, "tile index out of range");
  info.key = TileKey{static_cast<int>(ix), static_cast<int>(iy)};
  if (c.string(t, "key", path) != info.key.str()) c.bad(path + ".key", "does not match ix, iy");
  info.bounds_W = c.box(t, "bounds_enu", path);
  info.triangles = c.count(t, "triangles", path);
  info.points = c.count(t, "points", path);
  if (info.triangles == 0 && info.points == 0) c.bad(path, "is an empty tile (empty tiles are not stored)");
  const std::vector<double> o = c.numbers(t, "offset_enu", path, 3);
  info.origin_W = Eigen::Vector3d(o[0], o[1], o[2]);
  const json& files = c.at(t, "files", path);
  const json& bytes = c.at(t, "bytes", path);
  for (const bool points : {false, true}) {
    const char* kind = points ? "points" : "mesh";
    const bool present = (points ? info.points : info.triangles) > 0;
    const json& f = c.at(files, kind, path + ".files");
    const std::string fpath = path + ".files." + kind;
    // File names follow from the key; the index states them for readers, and a mismatch means it was edited wrongly.
    if (present && (!f.is_string() || f.get<std::string>() != tile_file_name(info.key, points))) {
      c.bad(fpath, "must be \"" + tile_file_name(info.key, points) + "\"");
    }
    if (!present && !f.is_null()) c.bad(fpath, "must be null when the tile has no " + std::string(kind));
    const std::size_t b = c.count(bytes, kind, path + ".bytes");
    if (present != (b > 0)) c.bad(path + ".bytes." + kind, "contradicts the tile's counts");
    (points ? info.points_bytes : info.mesh_bytes) = b;
  }
  info.bytes = info.mesh_bytes + info.points_bytes;
  return info;
}

}  // namespace

std::string tile_file_name(const TileKey& key, bool points) {
  return "tiles/" + key.str() + (points ? ".points.drc" : ".mesh.drc");
}

void write_twin_index(const TwinIndex& index, const std::string& twin_dir) {
  json tiles = json::array();
  for (const TileInfo& t : index.tiles) {
    tiles.push_back({{"key", t.key.str()},
                     {"ix", t.key.ix},
                     {"iy", t.key.iy},
                     {"bounds_enu", box_json(t.bounds_W)},
                     {"triangles", t.triangles},
                     {"points", t.points},
                     {"files",
                      {{"mesh", t.triangles > 0 ? json(tile_file_name(t.key, false)) : json(nullptr)},
                       {"points", t.points > 0 ? json(tile_file_name(t.key, true)) : json(nullptr)}}},
                     {"bytes", {{"mesh", t.mesh_bytes}, {"points", t.points_bytes}}},
                     {"offset_enu", {t.origin_W.x(), t.origin_W.y(), t.origin_W.z()}}});
  }
  const json j = {{"format", "twinslam-twin"},
                  {"format_version", kTwinFormatVersion},
                  {"origin", {index.origin.lat_deg, index.origin.lon_deg, index.origin.alt_m}},
                  {"twin_id", index.twin_id},
                  {"tile_size_m", index.tile_size_m},
                  {"point_spacing_m", index.point_spacing_m},
                  {"extent_enu", box_json(index.extent_W)},
                  {"totals", {{"tiles", index.tiles.size()}, {"triangles", index.triangles}, {"points", index.points}}},
                  {"tiles", tiles}};
  const fs::path path = fs::path(twin_dir) / "index.json", tmp = fs::path(twin_dir) / "index.json.tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(1) << '\n';
    if (!out) throw InputError(where(tmp.string(), 0, "cannot write"));
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw InputError(where(path.string(), 0, "cannot write: " + ec.message()));
}

TwinIndex read_twin_index(const std::string& twin_dir) {
  const std::string file = (fs::path(twin_dir) / "index.json").string();
  std::ifstream in(file);
  if (!in) throw InputError(where(file, 0, "cannot read (not a twin store built by 'twinslam twin build'?)"));
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(where(file, 0, std::string("not valid JSON: ") + e.what()));
  }
  const Checked c(file);
  TwinIndex index;
  if (c.string(j, "format", "") != "twinslam-twin") c.bad("format", "must be \"twinslam-twin\"");
  index.format_version = static_cast<int>(c.integer(j, "format_version", ""));
  if (index.format_version != kTwinFormatVersion) {
    c.bad("format_version",
          "is " + std::to_string(index.format_version) + ", this build reads " + std::to_string(kTwinFormatVersion));
  }
  const std::vector<double> o = c.numbers(j, "origin", "", 3);
  if (std::abs(o[0]) > 90.0 || std::abs(o[1]) > 180.0) c.bad("origin", "is not a WGS84 latitude, longitude");
  index.origin = GeoOrigin{o[0], o[1], o[2]};
  index.twin_id = c.string(j, "twin_id", "");
  if (index.twin_id.empty()) c.bad("twin_id", "is empty");
  index.tile_size_m = c.number(j, "tile_size_m", "");
  if (!(index.tile_size_m > 0.0)) c.bad("tile_size_m", "must be positive");
  index.point_spacing_m = c.number(j, "point_spacing_m", "");
  if (!(index.point_spacing_m > 0.0)) c.bad("point_spacing_m", "must be positive");
  index.extent_W = c.box(j, "extent_enu", "");
  const json& totals = c.at(j, "totals", "");
  index.triangles = c.count(totals, "triangles", "totals");
  index.points = c.count(totals, "points", "totals");
  const std::size_t n_tiles = c.count(totals, "tiles", "totals");
  const json& tiles = c.at(j, "tiles", "");
  if (!tiles.is_array()) c.bad("tiles", "must be an array");
  std::set<TileKey> seen;
  std::size_t triangles = 0, points = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const std::string path = "tiles[" + std::to_string(i) + "]";
    TileInfo info = read_tile(c, tiles[i], path);
    if (!seen.insert(info.key).second) c.bad(path + ".key", "repeats tile " + info.key.str());
    triangles += info.triangles;
    points += info.points;
    index.tiles.push_back(std::move(info));
  }
  if (n_tiles != index.tiles.size()) c.bad("totals.tiles", "differs from the number of tiles listed");
  if (triangles != index.triangles) c.bad("totals.triangles", "differs from the sum over the tiles");
  if (points != index.points) c.bad("totals.points", "differs from the sum over the tiles");
  std::sort(index.tiles.begin(), index.tiles.end(), [](const TileInfo& a, const TileInfo& b) { return a.key < b.key; });
  return index;
}

}  // namespace twinslam::twin
