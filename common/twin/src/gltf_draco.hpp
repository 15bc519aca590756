#pragma once
// Private: decoding of one KHR_draco_mesh_compression primitive, kept apart from tinygltf so that the Draco headers
// and tinygltf meet in no translation unit. tinygltf's own Draco path is not used: it indexes bufferViews and Draco
// attributes without checking them, and it ignores decode failures (see gltf.cpp).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace twinslam::twin::detail {

struct DracoPrimitive {
  std::vector<Eigen::Vector3d> positions;   // model frame [m], dequantized
  std::vector<Eigen::Vector3i> triangles;   // indices into positions
  std::vector<std::uint32_t> batch_id;      // per position if batch_attribute_id >= 0
};

// position_id / batch_attribute_id: the Draco attribute unique ids named in the extension (batch < 0: none).
// Throws InputError naming `name` on a decode failure or a missing / malformed attribute.
DracoPrimitive decode_draco_primitive(const std::uint8_t* data, std::size_t size, int position_id,
                                      int batch_attribute_id, const std::string& name);

}  // namespace twinslam::twin::detail
