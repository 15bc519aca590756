#pragma once
// glTF 2.0 (JSON .gltf or binary .glb) -> one triangle Mesh, through tinygltf (kept out of this header).
// The result stays in the glTF model frame (y-up, metres): the default scene's node transforms (matrix or TRS, the
// whole hierarchy) are applied, but not the y-up -> z-up turn — that belongs to the caller (3D Tiles content, or
// load_twin_source for a standalone model). Read: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (points and
// lines skipped), indexed or not, any accessor component type (normalized ones dequantized), and
// KHR_draco_mesh_compression. The CESIUM_RTC extension's center (given z-up, like a b3dm RTC_CENTER) is added after
// turning it into the y-up model frame, so "turn to z-up" gives the same point either way.
// Every problem (bad magic or chunk, missing buffer, accessor out of range, Draco decode failure ...) throws
// InputError naming the file (name_for_errors) and the reason.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

// A glTF model plus the per-vertex batch id that 3D Tiles (b3dm) content carries.
struct GltfContent {
  Mesh mesh;                           // y-up model frame [m]; p_W holds model coordinates here
  std::vector<std::uint32_t> batch_id; // per vertex, from _BATCHID (or legacy BATCHID / batchId); empty if absent
  bool cesium_rtc = false;             // the deprecated CESIUM_RTC extension placed it
};

// base_dir: where a JSON glTF's relative buffer URIs are looked up ("" = none allowed but data: URIs).
GltfContent load_gltf_content(const std::uint8_t* data, std::size_t size, const std::string& name_for_errors,
                              const std::string& base_dir = "");

Mesh load_gltf_memory(const std::uint8_t* data, std::size_t size, const std::string& name_for_errors);
Mesh load_gltf_file(const std::string& path);

// The 3D Tiles / glTF up-axis rule: glTF y-up to z-up is +90 deg about X, (x, y, z) -> (x, -z, y).
inline Eigen::Vector3d gltf_y_up_to_z_up(const Eigen::Vector3d& p) { return {p.x(), -p.z(), p.y()}; }
inline Eigen::Vector3d gltf_z_up_to_y_up(const Eigen::Vector3d& p) { return {p.x(), p.z(), -p.y()}; }

// Whole file into memory; throws InputError "<path>: cannot read ..." when it cannot.
std::vector<std::uint8_t> read_binary_file(const std::string& path);

}  // namespace twinslam::twin
