// 3D Tiles content loading and placement in W (order of the transforms: see tiles3d.hpp), and load_3dtiles.
#include "twinslam/twin/tiles3d.hpp"

#include <cstring>
#include <filesystem>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/gltf.hpp"

namespace twinslam::twin {
namespace {

bool magic_is(const std::vector<std::uint8_t>& b, const char* m) { return b.size() >= 4 && std::memcmp(b.data(), m, 4) == 0; }

// Model (y-up) -> tile frame (z-up, + RTC) -> ECEF -> W, vertex by vertex.
void place(Mesh& mesh, const Eigen::Vector3d& rtc_tile, const Eigen::Matrix4d& T_ECEF_tile, const EnuFrame& enu) {
  for (Eigen::Vector3d& p : mesh.p_W) {
    const Eigen::Vector3d p_tile = gltf_y_up_to_z_up(p) + rtc_tile;
    const Eigen::Vector3d p_ECEF = (T_ECEF_tile * p_tile.homogeneous()).head<3>();
    p = enu.from_ecef(p_ECEF);
  }
  mesh.n_W.clear();  // the Mesh carries no normals from glTF; keep the invariant explicit
}

}  // namespace

Mesh load_tile_content(const TileContentRef& content, const EnuFrame& enu, std::vector<std::uint32_t>* batch_id,
                       BatchTable* batch_table) {
  const std::vector<std::uint8_t> bytes = read_binary_file(content.path);
  GltfContent model;
  Eigen::Vector3d rtc = Eigen::Vector3d::Zero();
  if (magic_is(bytes, "b3dm")) {
    B3dmContent b3dm = parse_b3dm(bytes.data(), bytes.size(), content.path, B3dmCheck::kLenient);
    model = std::move(b3dm.gltf);
    if (b3dm.rtc_center) rtc = *b3dm.rtc_center;
    if (batch_table != nullptr) *batch_table = std::move(b3dm.batch_table);
  } else if (magic_is(bytes, "glTF") || std::filesystem::path(content.path).extension() == ".gltf") {
    const std::string dir = std::filesystem::path(content.path).parent_path().string();
    model = load_gltf_content(bytes.data(), bytes.size(), content.path, dir.empty() ? "." : dir);
    if (batch_table != nullptr) *batch_table = {};
  } else if (magic_is(bytes, "pnts") || magic_is(bytes, "i3dm") || magic_is(bytes, "cmpt")) {
    throw InputError(where(content.path, 0, std::string(reinterpret_cast<const char*>(bytes.data()), 4) +
                                                " content not supported (b3dm and glTF only), skipped"));
  } else {
    throw InputError(where(content.path, 0, "unknown tile content (no b3dm / glTF magic)"));
  }
  place(model.mesh, rtc, content.T_ECEF_tile, enu);
  if (batch_id != nullptr) *batch_id = std::move(model.batch_id);
  return std::move(model.mesh);
}

Mesh load_3dtiles(const std::string& tileset_json, const LoadOptions& options, LoadReport* report) {
  const std::vector<TileContentRef> contents = select_3dtiles_contents(tileset_json, options.max_geometric_error_m, report);
  const EnuFrame enu(options.origin);
  Mesh mesh_W;
  for (const TileContentRef& c : contents) {
    try {
      mesh_W.append(load_tile_content(c, enu));
      if (report != nullptr) ++report->parts_loaded;
    } catch (const InputError& e) {
      if (report != nullptr) report->rejected.emplace_back(e.what());
    }
  }
  return mesh_W;
}

}  // namespace twinslam::twin
