#pragma once
// Private: reading one glTF primitive's geometry (positions, triangle indices, batch ids) with every index, offset
// and length checked against its accessor, bufferView and buffer. tinygltf types are only forward-declared here.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace twinslam::twin::detail {

struct PrimitiveGeometry {
  std::vector<Eigen::Vector3d> positions;  // model frame [m], before the node transform
  std::vector<Eigen::Vector3i> triangles;  // TRIANGLES as given; STRIP / FAN converted; empty for points / lines
  std::vector<std::uint32_t> batch_id;     // per position when the primitive has _BATCHID / BATCHID / batchId
};

// Throws InputError naming `name` (and mesh_index) and the problem.
PrimitiveGeometry read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                 std::size_t mesh_index, const std::string& name);

}  // namespace twinslam::twin::detail
