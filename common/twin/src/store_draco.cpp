// Draco encoding and decoding of a tile's mesh and point set (store.hpp). Positions are written relative to an origin
// (float32 keeps ~0.5 mm at 5 km but ~4 um at 50 m) and that origin travels in the file's geometry metadata.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <draco/point_cloud/point_cloud_builder.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "draco_guard.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::twin {
namespace {

constexpr const char* kOriginKey = "twinslam_origin_W";  // metadata entry: 3 doubles [m, W]

void check_finite(const std::vector<Eigen::Vector3d>& v, const std::string& what) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].allFinite())
      throw InputError(where("draco encode", 0, what + " " + std::to_string(i) + " is not finite"));
  }
}

Eigen::Vector3d choose_origin(const std::vector<Eigen::Vector3d>& p_W, const std::optional<Eigen::Vector3d>& given) {
  if (given) return *given;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : p_W) box.extend(p);
  return box.min().array().floor().matrix();  // whole metres: a readable offset, |p - origin| stays within the box
}

void add_origin_metadata(draco::PointCloud* pc, const Eigen::Vector3d& origin_W) {
  auto metadata = std::make_unique<draco::GeometryMetadata>();
  metadata->AddEntryDoubleArray(kOriginKey, {origin_W.x(), origin_W.y(), origin_W.z()});
  pc->AddMetadata(std::move(metadata));
}

std::vector<std::uint8_t> encode(const draco::PointCloud* pc, const draco::Mesh* mesh, const StoreConfig& config) {
  config.validate();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, config.position_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, config.normal_bits);
  encoder.SetSpeedOptions(5, 5);  // Draco's default trade-off, pinned so files do not change with library defaults
  draco::EncoderBuffer buffer;
  const draco::Status status =
      mesh ? encoder.EncodeMeshToBuffer(*mesh, &buffer) : encoder.EncodePointCloudToBuffer(*pc, &buffer);
  if (!status.ok()) throw std::runtime_error("draco encode failed: " + status.error_msg_string());
  return {buffer.data(), buffer.data() + buffer.size()};
}

}  // namespace

std::vector<std::uint8_t> encode_mesh(const Mesh& mesh_W, const StoreConfig& config,
                                      const std::optional<Eigen::Vector3d>& origin_W) {
  if (mesh_W.triangles.empty()) throw InputError(where("draco encode", 0, "mesh has no triangles"));
  check_finite(mesh_W.p_W, "vertex");
  const Eigen::Vector3d origin = choose_origin(mesh_W.p_W, origin_W);
  const std::size_t n = mesh_W.p_W.size();
  draco::Mesh dm;
  draco::GeometryAttribute ga;
  ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int att_id =
      dm.AddAttribute(ga, /*identity_mapping=*/true, static_cast<draco::AttributeValueIndex::ValueType>(n));
  dm.set_num_points(static_cast<draco::PointIndex::ValueType>(n));
  draco::PointAttribute* att = dm.attribute(att_id);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f p = (mesh_W.p_W[i] - origin).cast<float>();
    att->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)), p.data());
  }
  for (std::size_t t = 0; t < mesh_W.triangles.size(); ++t) {
    const Eigen::Vector3i& f = mesh_W.triangles[t];
    if ((f.array() < 0).any() || (f.array().cast<std::size_t>() >= n).any()) {
      throw InputError(where("draco encode", 0, "triangle " + std::to_string(t) + " references a missing vertex"));
    }
    dm.AddFace({draco::PointIndex(f[0]), draco::PointIndex(f[1]), draco::PointIndex(f[2])});
  }
  add_origin_metadata(&dm, origin);
  return encode(nullptr, &dm, config);
}

std::vector<std::uint8_t> encode_points(const Mesh& points_W, const StoreConfig& config,
                                        const std::optional<Eigen::Vector3d>& origin_W) {
  if (points_W.p_W.empty()) throw InputError(where("draco encode", 0, "point set is empty"));
  if (points_W.n_W.size() != points_W.p_W.size()) {
    throw InputError(where("draco encode", 0, "point set needs one normal per point"));
  }
  check_finite(points_W.p_W, "point");
  check_finite(points_W.n_W, "normal");
  const Eigen::Vector3d origin = choose_origin(points_W.p_W, origin_W);
  const std::size_t n = points_W.p_W.size();
  draco::PointCloudBuilder builder;
  builder.Start(static_cast<draco::PointIndex::ValueType>(n));
  const int pos_id = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm_id = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  for (std::size_t i = 0; i < n; ++i) {
    const draco::PointIndex pi(static_cast<std::uint32_t>(i));
    const Eigen::Vector3f p = (points_W.p_W[i] - origin).cast<float>();
    const double norm = points_W.n_W[i].norm();
    // Draco's octahedral normal coding expects unit vectors; a zero normal stays zero-ish (+z) rather than NaN.
    const Eigen::Vector3f nv =
        norm > 0 ? Eigen::Vector3f((points_W.n_W[i] / norm).cast<float>()) : Eigen::Vector3f(0, 0, 1);
    builder.SetAttributeValueForPoint(pos_id, pi, p.data());
    builder.SetAttributeValueForPoint(nrm_id, pi, nv.data());
  }
  std::unique_ptr<draco::PointCloud> pc = builder.Finalize(/*deduplicate_points=*/false);
  if (!pc) throw std::runtime_error("draco point cloud builder failed");
  add_origin_metadata(pc.get(), origin);
  return encode(pc.get(), nullptr, config);
}

Mesh decode_draco(const std::uint8_t* data, std::size_t size, const std::string& what) {
  const auto fail = [&](const std::string& why) {
    return InputError(where(what, 0, "not a valid Draco file: " + why));
  };
  if (data == nullptr || size == 0) throw fail("empty");
  if (const std::string problem = detail::draco_count_problem(data, size); !problem.empty()) throw fail(problem);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) throw fail(type.status().error_msg_string());
  draco::Decoder decoder;
  std::unique_ptr<draco::PointCloud> pc;
  const draco::Mesh* dm = nullptr;
  if (type.value() == draco::TRIANGULAR_MESH) {
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) throw fail(decoded.status().error_msg_string());
    dm = decoded.value().get();
    pc = std::move(decoded).value();
  } else if (type.value() == draco::POINT_CLOUD) {
    auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
    if (!decoded.ok()) throw fail(decoded.status().error_msg_string());
    pc = std::move(decoded).value();
  } else {
    throw fail("unknown geometry type");
  }
  const draco::PointAttribute* pos = pc->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (pos == nullptr || pos->num_components() != 3) throw fail("no 3D POSITION attribute");
  const draco::PointAttribute* nrm = pc->GetNamedAttribute(draco::GeometryAttribute::NORMAL);
  if (nrm != nullptr && nrm->num_components() != 3) throw fail("NORMAL attribute is not 3D");
  // Draco converts a boolean attribute by loading each byte as a C++ bool, undefined for bytes other than 0 and 1
  // (fuzzing found it): geometry is never boolean, so such a file is refused.
  if (pos->data_type() == draco::DT_BOOL || (nrm != nullptr && nrm->data_type() == draco::DT_BOOL)) {
    throw fail("boolean POSITION or NORMAL attribute");
  }

  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // a Draco file from elsewhere: positions are already in W
  std::vector<double> o;
  if (pc->GetMetadata() != nullptr && pc->GetMetadata()->GetEntryDoubleArray(kOriginKey, &o)) {
    if (o.size() != 3 || !std::isfinite(o[0]) || !std::isfinite(o[1]) || !std::isfinite(o[2])) {
      throw fail(std::string("bad ") + kOriginKey + " metadata");
    }
    origin = Eigen::Vector3d(o[0], o[1], o[2]);
  }
  const std::uint32_t n = pc->num_points();
  // Draco reads attribute values without bounds checks: check every point's value index before converting.
  const auto value_index = [&](const draco::PointAttribute* att, std::uint32_t i) {
    if (!att->is_mapping_identity() && att->indices_map_size() < n) throw fail("attribute map shorter than the points");
    if (att->buffer() == nullptr || att->buffer()->data_size() < att->size() * att->byte_stride()) {
      throw fail("attribute data shorter than its values");
    }
    const draco::AttributeValueIndex v = att->mapped_index(draco::PointIndex(i));
    if (v.value() >= att->size()) throw fail("attribute value index out of range");
    return v;
  };
  Mesh out;
  out.p_W.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    float v[3];
    if (!pos->ConvertValue<float, 3>(value_index(pos, i), v)) throw fail("unreadable position");
    out.p_W.push_back(origin + Eigen::Vector3d(v[0], v[1], v[2]));
    if (nrm != nullptr) {
      if (!nrm->ConvertValue<float, 3>(value_index(nrm, i), v)) throw fail("unreadable normal");
      out.n_W.push_back(Eigen::Vector3d(v[0], v[1], v[2]).normalized());
    }
  }
  if (dm != nullptr) {
    out.triangles.reserve(dm->num_faces());
    for (std::uint32_t f = 0; f < dm->num_faces(); ++f) {
      const draco::Mesh::Face& face = dm->face(draco::FaceIndex(f));
      for (int k = 0; k < 3; ++k) {
        if (face[k].value() >= n) throw fail("face " + std::to_string(f) + " references a missing point");
      }
      out.triangles.emplace_back(face[0].value(), face[1].value(), face[2].value());
    }
  }
  return out;
}

}  // namespace twinslam::twin
