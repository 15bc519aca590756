// KHR_draco_mesh_compression: one compressed primitive -> positions, triangles, batch ids (draco 1.5).
#include "gltf_draco.hpp"

#include <cmath>

#include <draco/compression/decode.h>

#include "draco_guard.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::twin::detail {
namespace {

const draco::PointAttribute* attribute(const draco::Mesh& mesh, int unique_id, int min_components,
                                       const std::string& what, const std::string& name) {
  if (unique_id < 0) throw InputError(where(name, 0, "Draco " + what + " attribute id is negative"));
  const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(static_cast<std::uint32_t>(unique_id));
  if (att == nullptr) {
    throw InputError(where(name, 0, "Draco data has no attribute with id " + std::to_string(unique_id) +
                                        " (" + what + ")"));
  }
  // Draco loads a boolean attribute's bytes as C++ bools, undefined for values other than 0 and 1 (store_draco.cpp).
  if (att->data_type() == draco::DT_BOOL) {
    throw InputError(where(name, 0, "Draco " + what + " attribute is boolean"));
  }
  if (att->num_components() < min_components) {
    throw InputError(where(name, 0, "Draco " + what + " attribute has " +
                                        std::to_string(att->num_components()) + " components"));
  }
  return att;
}

}  // namespace

DracoPrimitive decode_draco_primitive(const std::uint8_t* data, std::size_t size, int position_id,
                                      int batch_attribute_id, const std::string& name) {
  if (const std::string problem = draco_count_problem(data, size); !problem.empty()) {
    throw InputError(where(name, 0, "Draco data " + problem));
  }
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    throw InputError(where(name, 0, "Draco decode failure: " + decoded.status().error_msg_string()));
  }
  const draco::Mesh& mesh = *decoded.value();
  const draco::PointAttribute* pos = attribute(mesh, position_id, 3, "POSITION", name);
  const draco::PointAttribute* batch =
      batch_attribute_id >= 0 ? attribute(mesh, batch_attribute_id, 1, "batch id", name) : nullptr;

  DracoPrimitive out;
  const std::uint32_t n = mesh.num_points();
  out.positions.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const draco::PointIndex point(i);
    float xyz[3] = {0.0F, 0.0F, 0.0F};
    if (!pos->ConvertValue<float>(pos->mapped_index(point), 3, xyz)) {
      throw InputError(where(name, 0, "Draco POSITION of point " + std::to_string(i) + " unreadable"));
    }
    out.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (batch != nullptr) {
      float id = 0.0F;
      if (!batch->ConvertValue<float>(batch->mapped_index(point), 1, &id) || !(id >= 0.0F)) {
        throw InputError(where(name, 0, "Draco batch id of point " + std::to_string(i) + " unreadable"));
      }
      out.batch_id.push_back(static_cast<std::uint32_t>(std::lround(id)));
    }
  }
  out.triangles.reserve(mesh.num_faces());
  for (std::uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    Eigen::Vector3i tri(static_cast<int>(face[0].value()), static_cast<int>(face[1].value()),
                        static_cast<int>(face[2].value()));
    if ((tri.array() < 0).any() || (tri.array() >= static_cast<int>(n)).any()) {
      throw InputError(where(name, 0, "Draco face " + std::to_string(f) + " indexes a missing point"));
    }
    out.triangles.push_back(tri);
  }
  return out;
}

}  // namespace twinslam::twin::detail
