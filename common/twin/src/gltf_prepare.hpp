#pragma once
// Private: makes a Draco-compressed glTF acceptable to tinygltf without tinygltf's own Draco decoder (see gltf.cpp).
// tinygltf refuses an index accessor without a bufferView, which is exactly how KHR_draco_mesh_compression
// primitives look (the Draco stream holds the faces). Such primitives lose their "indices" member here; their
// geometry is then decoded from the Draco stream by gltf_draco.cpp.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "glb.hpp"

namespace twinslam::twin::detail {

// The bytes to give tinygltf instead of the input, or nullopt when nothing needs changing (no Draco primitive with
// indices, or JSON that tinygltf shall report as malformed itself). glb: the checked chunks when the input is a GLB.
std::optional<std::vector<std::uint8_t>> drop_draco_indices(const std::uint8_t* data, std::size_t size,
                                                            const GlbChunks* glb);

}  // namespace twinslam::twin::detail
