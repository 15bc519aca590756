// 3D Tiles tileset traversal: validation of each tile, transform chaining, refinement and level choice, external
// tilesets (see tiles3d.hpp for the rules).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tiles3d_quirks.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/tiles3d.hpp"

namespace twinslam::twin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kMaxDepth = 64;  // tile nesting plus external tilesets; deeper is a cycle or a broken file

bool numbers(const json& a, std::size_t n) {
  if (!a.is_array() || a.size() != n) return false;
  return std::all_of(a.begin(), a.end(), [](const json& v) { return v.is_number() && std::isfinite(v.get<double>()); });
}

void check_volume(const json& tile, const std::string& file, const std::string& at) {
  auto bad = [&](const std::string& what) { return InputError(where(file, 0, at + ": " + what)); };
  if (!tile.contains("boundingVolume") || !tile["boundingVolume"].is_object()) throw bad("boundingVolume missing");
  const json& bv = tile["boundingVolume"];
  if (bv.contains("region")) {
    if (!numbers(bv["region"], 6)) throw bad("region is not 6 finite numbers");
    const json& r = bv["region"];  // [west, south, east, north] radians, [min, max] height metres
    const double w = r[0], s = r[1], e = r[2], n = r[3];
    const double pi = std::numbers::pi;
    if (w < -pi || w > pi || e < -pi || e > pi) throw bad("region longitude outside [-pi, pi] (radians)");
    if (s < -pi / 2 || n > pi / 2 || s > n) throw bad("region latitude outside [-pi/2, pi/2] or south > north");
    if (r[4].get<double>() > r[5].get<double>()) throw bad("region minimum height > maximum height");
  } else if (bv.contains("box")) {
    if (!numbers(bv["box"], 12)) throw bad("box is not 12 finite numbers");
  } else if (bv.contains("sphere")) {
    if (!numbers(bv["sphere"], 4)) throw bad("sphere is not 4 finite numbers");
    if (bv["sphere"][3].get<double>() < 0) throw bad("sphere radius is negative");
  } else {
    throw bad("boundingVolume has none of box, region, sphere");
  }
}

Eigen::Matrix4d tile_transform(const json& tile, const std::string& file, const std::string& at) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  if (!tile.contains("transform")) return T;
  if (!numbers(tile["transform"], 16)) throw InputError(where(file, 0, at + ": transform is not 16 finite numbers"));
  for (int i = 0; i < 16; ++i) T(i % 4, i / 4) = tile["transform"][static_cast<std::size_t>(i)].get<double>();
  if (!T.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1))) {
    throw InputError(where(file, 0, at + ": transform is not affine (last row must be 0 0 0 1)"));
  }
  return T;
}

// uri relative to the tileset's folder; query / fragment dropped, %XX decoded. Empty when not a local file.
std::string resolve(const std::string& uri, const fs::path& dir) {
  if (uri.find("://") != std::string::npos) return {};
  std::string u = uri.substr(0, uri.find_first_of("?#"));
  std::string decoded;
  for (std::size_t i = 0; i < u.size(); ++i) {
    if (u[i] == '%' && i + 2 < u.size() && std::isxdigit(static_cast<unsigned char>(u[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(u[i + 2]))) {
      decoded += static_cast<char>(std::stoi(u.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += u[i];
    }
  }
  return (dir / decoded).lexically_normal().string();
}

std::string canonical(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  return ec ? fs::path(path).lexically_normal().string() : p.string();
}

bool ends_with_json(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".json";
}

struct Selector {
  double tau;
  bool strict;
  LoadReport* report;
  std::vector<TileContentRef> out;
  std::vector<std::string> chain;  // tileset files being walked (external tileset cycles)

  void reject(const std::string& line) {
    if (report != nullptr) report->rejected.push_back(line);
  }

  void quirk(detail::Quirk q, const std::string& file, const std::string& at) {
    detail::note_quirk(q, file, at, strict, report);
  }

  // asset.version: 1.0 / 1.1; a missing one and pre-1.0 "0.0" are quirks read as 1.0.
  void check_version(const json& j, const std::string& path) {
    if (!j.contains("asset") || !j["asset"].is_object()) throw InputError(where(path, 0, "tileset lacks asset"));
    const json& asset = j["asset"];
    if (!asset.contains("version")) return quirk(detail::Quirk::kNoAssetVersion, path, "asset");
    if (!asset["version"].is_string()) throw InputError(where(path, 0, "tileset asset.version is not a string"));
    const std::string version = asset["version"];
    if (version == "0.0") return quirk(detail::Quirk::kPreReleaseVersion, path, "asset");
    if (version != "1.0" && version != "1.1") {
      throw InputError(where(path, 0, "tileset asset.version '" + version + "' unsupported (1.0, 1.1)"));
    }
  }

  // The tile's geometricError; a missing one is the parent's (CesiumJS's fallback), the root's the tileset's.
  double geometric_error(const json& t, double parent_error, const std::string& file, const std::string& at) {
    if (!t.contains("geometricError")) {
      if (!(parent_error >= 0)) throw InputError(where(file, 0, at + ": geometricError missing (and no parent's)"));
      quirk(detail::Quirk::kNoGeometricError, file, at);
      return parent_error;
    }
    if (!t["geometricError"].is_number() || !(t["geometricError"].get<double>() >= 0)) {
      throw InputError(where(file, 0, at + ": geometricError is not a number >= 0"));
    }
    return t["geometricError"];
  }

  // Throws InputError for a malformed tileset file.
  void tileset(const std::string& path, const Eigen::Matrix4d& T_parent, int depth) {
    std::ifstream in(path);
    if (!in) throw InputError(where(path, 0, "cannot open tileset"));
    std::stringstream ss;
    ss << in.rdbuf();
    const json j = json::parse(ss.str(), nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) throw InputError(where(path, 0, "tileset JSON is malformed"));
    if (!j.is_object()) throw InputError(where(path, 0, "tileset JSON is not an object"));
    check_version(j, path);
    if (!j.contains("root") || !j["root"].is_object()) throw InputError(where(path, 0, "tileset lacks a root tile"));
    // The spec requires refine on the root; without one CesiumJS assumes REPLACE (with a warning), and so do we.
    if (!j["root"].contains("refine")) quirk(detail::Quirk::kNoRootRefine, path, "root");
    // The tileset's own geometricError stands in for a root that lacks one (-1: neither has one).
    const double tileset_error = j.contains("geometricError") && j["geometricError"].is_number()
                                     ? j["geometricError"].get<double>() : -1.0;
    chain.push_back(canonical(path));
    tile(j["root"], path, fs::path(path).parent_path(), T_parent, "REPLACE", tileset_error, "root", depth);
    chain.pop_back();
  }

  void tile(const json& t, const std::string& file, const fs::path& dir, const Eigen::Matrix4d& T_parent,
            const std::string& parent_refine, double parent_error, const std::string& at, int depth) {
    if (depth > kMaxDepth) {
      throw InputError(where(file, 0, at + ": tiles nested deeper than " + std::to_string(kMaxDepth)));
    }
    if (!t.is_object()) throw InputError(where(file, 0, at + ": tile is not an object"));
    const double error = geometric_error(t, parent_error, file, at);
    if (t.contains("implicitTiling")) {
      reject(file + ": " + at + ": implicit tiling not supported, subtree skipped");
      return;
    }
    check_volume(t, file, at);
    const Eigen::Matrix4d T = T_parent * tile_transform(t, file, at);
    std::string refine = parent_refine;
    if (t.contains("refine")) {
      if (!t["refine"].is_string()) throw InputError(where(file, 0, at + ": refine is not a string"));
      refine = t["refine"];
      std::transform(refine.begin(), refine.end(), refine.begin(), [](unsigned char c) { return std::toupper(c); });
      if (refine != "ADD" && refine != "REPLACE") {
        throw InputError(where(file, 0, at + ": refine '" + refine + "' is neither ADD nor REPLACE"));
      }
    }
    const json* children = t.contains("children") ? &t["children"] : nullptr;
    if (children != nullptr && !children->is_array()) {
      throw InputError(where(file, 0, at + ": children is not an array"));
    }
    const bool leaf = children == nullptr || children->empty();
    const bool enough = error <= tau || leaf;  // this level is fine enough: its content, not its children's
    if (enough || refine == "ADD") contents(t, file, dir, T, error, at, depth);
    else external_only(t, file, dir, T, at, depth);
    if (enough) return;
    for (std::size_t i = 0; i < children->size(); ++i) {
      tile((*children)[i], file, dir, T, refine, error, at + "/" + std::to_string(i), depth + 1);
    }
  }

  std::vector<std::string> uris(const json& t, const std::string& file, const std::string& at) {
    std::vector<const json*> list;
    if (t.contains("content")) list.push_back(&t["content"]);
    if (t.contains("contents")) {
      if (!t["contents"].is_array()) throw InputError(where(file, 0, at + ": contents is not an array"));
      for (const json& c : t["contents"]) list.push_back(&c);
    }
    std::vector<std::string> out_uris;
    for (const json* c : list) {
      if (!c->is_object()) throw InputError(where(file, 0, at + ": content is not an object"));
      const char* key = c->contains("uri") ? "uri" : "url";  // 1.0 / 1.1 spell it uri, pre-1.0 url
      if (!c->contains(key) || !(*c)[key].is_string()) throw InputError(where(file, 0, at + ": content has no uri"));
      if (key[2] == 'l') quirk(detail::Quirk::kContentUrl, file, at);
      out_uris.push_back((*c)[key].get<std::string>());
    }
    return out_uris;
  }

  // Renderable contents are selected; external tilesets are walked (they stand for the tile's children).
  void contents(const json& t, const std::string& file, const fs::path& dir, const Eigen::Matrix4d& T, double error,
                const std::string& at, int depth) {
    for (const std::string& uri : uris(t, file, at)) {
      const std::string path = resolve(uri, dir);
      if (path.empty()) { reject(file + ": " + at + ": remote content '" + uri + "' not supported"); continue; }
      if (ends_with_json(path)) external(path, file, T, at, depth);
      else out.push_back({path, T, error});
    }
  }

  // REPLACE above tau: the tile's own renderable content is replaced, but an external tileset holds its children.
  void external_only(const json& t, const std::string& file, const fs::path& dir, const Eigen::Matrix4d& T,
                     const std::string& at, int depth) {
    for (const std::string& uri : uris(t, file, at)) {
      const std::string path = resolve(uri, dir);
      if (!path.empty() && ends_with_json(path)) external(path, file, T, at, depth);
    }
  }

  void external(const std::string& path, const std::string& file, const Eigen::Matrix4d& T, const std::string& at,
                int depth) {
    const std::string canon = canonical(path);
    if (std::find(chain.begin(), chain.end(), canon) != chain.end()) {
      reject(file + ": " + at + ": external tileset " + path + " refers back to itself (cycle), skipped");
      return;
    }
    const std::size_t chain_size = chain.size();
    try {
      tileset(path, T, depth + 1);
    } catch (const detail::QuirkRefused&) {
      throw;
    } catch (const InputError& e) {
      chain.resize(chain_size);  // unwound past tileset()'s pop
      reject(e.what());
    }
  }
};

}  // namespace

std::vector<TileContentRef> select_3dtiles_contents(const std::string& tileset_json, double max_geometric_error_m,
                                                    LoadReport* report, bool strict) {
  if (!(max_geometric_error_m >= 0)) throw UsageError("max_geometric_error_m must be >= 0");
  Selector s{max_geometric_error_m, strict, report, {}, {}};
  s.tileset(tileset_json, Eigen::Matrix4d::Identity(), 0);
  return std::move(s.out);
}

}  // namespace twinslam::twin
