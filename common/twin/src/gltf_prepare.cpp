// Removal of the index accessors of Draco primitives before tinygltf parses the JSON (see gltf_prepare.hpp).
#include "gltf_prepare.hpp"

#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

namespace twinslam::twin::detail {
namespace {

void put_u32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace

std::optional<std::vector<std::uint8_t>> drop_draco_indices(const std::uint8_t* data, std::size_t size,
                                                            const GlbChunks* glb) {
  const std::uint8_t* json_begin = glb != nullptr ? data + glb->json_offset : data;
  const std::size_t json_size = glb != nullptr ? glb->json_size : size;
  // Most models use no Draco: a byte search spares them a second JSON parse.
  static const std::string kDraco = "KHR_draco_mesh_compression";
  if (std::search(json_begin, json_begin + json_size, kDraco.begin(), kDraco.end()) == json_begin + json_size) {
    return std::nullopt;
  }
  nlohmann::json j = nlohmann::json::parse(json_begin, json_begin + json_size, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("meshes") || !j["meshes"].is_array()) return std::nullopt;
  bool changed = false;
  for (auto& mesh : j["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (auto& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("indices") || !prim.contains("extensions")) continue;
      const auto& ext = prim["extensions"];
      if (ext.is_object() && ext.contains("KHR_draco_mesh_compression")) {
        prim.erase("indices");
        changed = true;
      }
    }
  }
  if (!changed) return std::nullopt;
  std::string text = j.dump();
  if (glb == nullptr) return std::vector<std::uint8_t>(text.begin(), text.end());
  while (text.size() % 4 != 0) text.push_back(' ');  // GLB chunks stay 4-byte aligned
  // New GLB: header, the new JSON chunk, then every following chunk (BIN ...) unchanged.
  const std::size_t rest_at = glb->json_offset + glb->json_size;
  const std::size_t rest = glb->length - rest_at;
  std::vector<std::uint8_t> out;
  out.reserve(12 + 8 + text.size() + rest);
  out.insert(out.end(), data, data + 8);  // magic, version
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + rest));
  put_u32(out, static_cast<std::uint32_t>(text.size()));
  put_u32(out, 0x4E4F534AU);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), data + rest_at, data + glb->length);
  return out;
}

}  // namespace twinslam::twin::detail
