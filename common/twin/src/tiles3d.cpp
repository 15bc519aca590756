// 3D Tiles content loading and placement in W (order of the transforms: see tiles3d.hpp), and load_3dtiles.
#include "twinslam/twin/tiles3d.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>

#include "cmpt.hpp"
#include "tiles3d_quirks.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/gltf.hpp"

namespace twinslam::twin {
namespace {

bool magic_is(const std::uint8_t* d, std::size_t n, const char* m) { return n >= 4 && std::memcmp(d, m, 4) == 0; }

std::string unsupported(const std::uint8_t* magic, const std::string& name) {
  return where(name, 0, std::string(reinterpret_cast<const char*>(magic), 4) +
                            " content not supported (b3dm, glTF and cmpt only), skipped");
}

constexpr int kMaxCmptDepth = 8;  // composites of composites: deeper is garbage

// Model (y-up) -> tile frame (z-up, + RTC) -> ECEF -> W, vertex by vertex.
void place(Mesh& mesh, const Eigen::Vector3d& rtc_tile, const Eigen::Matrix4d& T_ECEF_tile, const EnuFrame& enu) {
  for (Eigen::Vector3d& p : mesh.p_W) {
    const Eigen::Vector3d p_tile = gltf_y_up_to_z_up(p) + rtc_tile;
    const Eigen::Vector3d p_ECEF = (T_ECEF_tile * p_tile.homogeneous()).head<3>();
    p = enu.from_ecef(p_ECEF);
  }
  mesh.n_W.clear();  // the Mesh carries no normals from glTF; keep the invariant explicit
}

struct ContentLoader {
  const TileContentRef& ref;
  const EnuFrame& enu;
  std::vector<std::uint32_t>* batch_id;
  BatchTable* batch_table;
  LoadReport* report;
  bool strict;
  Mesh out;

  // One tile's bytes (the file, or an inner tile of a composite, named `name`) appended to `out`.
  void load(const std::uint8_t* d, std::size_t n, const std::string& name, int depth) {
    GltfContent model;
    Eigen::Vector3d rtc = Eigen::Vector3d::Zero();
    if (magic_is(d, n, "b3dm")) {
      B3dmContent b3dm = parse_b3dm(d, n, name, B3dmCheck::kLenient);
      if (b3dm.header_bytes != 28) detail::note_quirk(detail::Quirk::kLegacyB3dmHeader, name, "header", strict, report);
      if (b3dm.unpadded) detail::note_quirk(detail::Quirk::kUnpaddedB3dm, name, "byteLength", strict, report);
      model = std::move(b3dm.gltf);
      if (b3dm.rtc_center) rtc = *b3dm.rtc_center;
      if (batch_table != nullptr) *batch_table = std::move(b3dm.batch_table);
    } else if (magic_is(d, n, "glTF") || (depth == 0 && std::filesystem::path(name).extension() == ".gltf")) {
      const std::string dir = std::filesystem::path(ref.path).parent_path().string();
      model = load_gltf_content(d, n, name, dir.empty() ? "." : dir);
    } else if (magic_is(d, n, "cmpt")) {
      if (depth >= kMaxCmptDepth) throw InputError(where(name, 0, "composites nested too deep"));
      const auto inner = detail::split_cmpt(d, n, name);
      for (std::size_t i = 0; i < inner.size(); ++i) {
        const std::string inner_name = name + " [inner tile " + std::to_string(i) + "]";
        const std::uint8_t* p = d + inner[i].offset;
        if (magic_is(p, inner[i].size, "pnts") || magic_is(p, inner[i].size, "i3dm")) {  // skip, but say so
          if (report != nullptr) report->rejected.push_back(unsupported(p, inner_name));
          continue;
        }
        load(p, inner[i].size, inner_name, depth + 1);
      }
      return;
    } else if (magic_is(d, n, "pnts") || magic_is(d, n, "i3dm")) {
      throw InputError(unsupported(d, name));
    } else {
      throw InputError(where(name, 0, "unknown tile content (no b3dm / glTF / cmpt magic)"));
    }
    if (model.cesium_rtc) detail::note_quirk(detail::Quirk::kCesiumRtc, name, "glTF extensions", strict, report);
    place(model.mesh, rtc, ref.T_ECEF_tile, enu);
    const std::size_t base = out.num_vertices();
    out.append(model.mesh);
    if (batch_id != nullptr) {
      if (model.batch_id.empty()) {  // content without batch ids: the "no feature" id keeps the vectors aligned
        model.batch_id.assign(model.mesh.num_vertices(), std::numeric_limits<std::uint32_t>::max());
      }
      batch_id->resize(base);
      batch_id->insert(batch_id->end(), model.batch_id.begin(), model.batch_id.end());
    }
  }
};

}  // namespace

Mesh load_tile_content(const TileContentRef& content, const EnuFrame& enu, std::vector<std::uint32_t>* batch_id,
                       BatchTable* batch_table, LoadReport* report, bool strict) {
  const std::vector<std::uint8_t> bytes = read_binary_file(content.path);
  if (batch_id != nullptr) batch_id->clear();
  if (batch_table != nullptr) *batch_table = {};
  ContentLoader loader{content, enu, batch_id, batch_table, report, strict, {}};
  loader.load(bytes.data(), bytes.size(), content.path, 0);
  if (batch_id != nullptr && std::all_of(batch_id->begin(), batch_id->end(), [](std::uint32_t id) {
        return id == std::numeric_limits<std::uint32_t>::max();
      })) {
    batch_id->clear();  // no content had batch ids
  }
  return std::move(loader.out);
}

Mesh load_3dtiles(const std::string& tileset_json, const LoadOptions& options, LoadReport* report) {
  const std::vector<TileContentRef> contents =
      select_3dtiles_contents(tileset_json, options.max_geometric_error_m, report, options.strict);
  const EnuFrame enu(options.origin);
  Mesh mesh_W;
  for (const TileContentRef& c : contents) {
    try {
      mesh_W.append(load_tile_content(c, enu, nullptr, nullptr, report, options.strict));
      if (report != nullptr) ++report->parts_loaded;
    } catch (const detail::QuirkRefused&) {
      throw;  // strict mode: a quirk fails the load instead of one part
    } catch (const InputError& e) {
      if (report != nullptr) report->rejected.emplace_back(e.what());
    }
  }
  return mesh_W;
}

}  // namespace twinslam::twin
