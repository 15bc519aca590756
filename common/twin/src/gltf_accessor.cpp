// Checked reading of glTF accessors (glTF 2.0 spec 3.6 "Binary data storage") and primitive topology (3.7.2.1).
// Same tinygltf configuration macros as gltf.cpp (the types must be identical); no implementation here.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>

#include "gltf_accessor.hpp"
#include "gltf_draco.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::twin::detail {
namespace {

struct Ctx {
  const tinygltf::Model& model;
  const std::string& name;
  std::string prefix;  // "mesh 3: "
  InputError error(const std::string& what) const { return InputError(where(name, 0, prefix + what)); }
};

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices are never geometry
  }
}

// Unaligned little-endian read (x86 and every platform Debian ships for this are little-endian).
template <typename T>
double load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

// One component as double; normalized integers map to [-1, 1] / [0, 1] (KHR_mesh_quantization, spec 3.11).
double component(const std::uint8_t* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    default: return 0.0;
  }
}

// Values of accessor `index` as doubles, `want` components per element (the accessor must have exactly that many).
std::vector<double> read_accessor(const Ctx& c, int index, int want, const char* role) {
  const std::string what = std::string(role) + " accessor " + std::to_string(index);
  if (index < 0 || static_cast<std::size_t>(index) >= c.model.accessors.size()) throw c.error(what + " out of range");
  const tinygltf::Accessor& acc = c.model.accessors[static_cast<std::size_t>(index)];
  if (acc.sparse.isSparse) throw c.error(what + " is sparse (not supported)");
  const int ncomp = component_count(acc.type);
  if (ncomp != want) {
    throw c.error(what + " has " + std::to_string(ncomp) + " components, expected " + std::to_string(want));
  }
  const int csize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(acc.componentType));
  if (csize <= 0 || acc.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE) {
    throw c.error(what + " has invalid componentType " + std::to_string(acc.componentType));
  }
  std::vector<double> values(acc.count * static_cast<std::size_t>(ncomp), 0.0);
  if (acc.count == 0) return values;
  if (acc.bufferView < 0) return values;  // spec: no bufferView and not sparse means all zeros
  if (static_cast<std::size_t>(acc.bufferView) >= c.model.bufferViews.size()) {
    throw c.error(what + " bufferView out of range");
  }
  const tinygltf::BufferView& view = c.model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= c.model.buffers.size()) {
    throw c.error(what + " bufferView " + std::to_string(acc.bufferView) + " names a missing buffer");
  }
  const std::vector<unsigned char>& buf = c.model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset) {
    throw c.error("bufferView " + std::to_string(acc.bufferView) + " runs past its buffer (" +
                  std::to_string(buf.size()) + " bytes)");
  }
  const std::size_t elem = static_cast<std::size_t>(csize) * static_cast<std::size_t>(ncomp);
  const std::size_t stride = view.byteStride > 0 ? view.byteStride : elem;
  if (stride < elem) throw c.error(what + " byteStride " + std::to_string(stride) + " < element size");
  // Last byte needed: byteOffset + stride * (count - 1) + elem, inside the view; written to avoid overflow.
  const std::size_t room = view.byteLength;
  if (acc.byteOffset > room || elem > room - acc.byteOffset ||
      (acc.count - 1) > (room - acc.byteOffset - elem) / stride) {
    throw c.error(what + " (" + std::to_string(acc.count) + " elements) runs past bufferView " +
                  std::to_string(acc.bufferView));
  }
  const std::uint8_t* base = buf.data() + view.byteOffset + acc.byteOffset;
  for (std::size_t i = 0; i < acc.count; ++i) {
    for (int k = 0; k < ncomp; ++k) {
      values[i * static_cast<std::size_t>(ncomp) + static_cast<std::size_t>(k)] =
          component(base + i * stride + static_cast<std::size_t>(k * csize), acc.componentType, acc.normalized);
    }
  }
  return values;
}

std::vector<Eigen::Vector3i> triangles_of(const Ctx& c, int mode, const std::vector<int>& idx, std::size_t nverts) {
  for (int i : idx) {
    if (i < 0 || static_cast<std::size_t>(i) >= nverts) {
      throw c.error("index " + std::to_string(i) + " >= vertex count " + std::to_string(nverts));
    }
  }
  std::vector<Eigen::Vector3i> tris;
  const std::size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t i = 0; i + 2 < n; i += 3) tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // Every other triangle of a strip is flipped to keep one winding (spec 3.7.2.1).
    for (std::size_t i = 0; i + 2 < n; ++i) {
      if (i % 2 == 0) tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
      else tris.emplace_back(idx[i + 1], idx[i], idx[i + 2]);
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 1; i + 1 < n; ++i) tris.emplace_back(idx[0], idx[i], idx[i + 1]);
  }
  // Strips and fans use repeated indices as restarts: drop the degenerate triangles they make.
  std::erase_if(tris, [](const Eigen::Vector3i& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; });
  return tris;
}

const char* const kBatchNames[] = {"_BATCHID", "BATCHID", "batchId"};

PrimitiveGeometry read_draco(const Ctx& c, const tinygltf::Primitive& prim, const tinygltf::Value& ext) {
  const tinygltf::Value& bv = ext.Get("bufferView");
  const tinygltf::Value& atts = ext.Get("attributes");
  if (!bv.IsInt() || !atts.IsObject()) throw c.error("KHR_draco_mesh_compression lacks bufferView / attributes");
  const int view_index = bv.Get<int>();
  if (view_index < 0 || static_cast<std::size_t>(view_index) >= c.model.bufferViews.size()) {
    throw c.error("KHR_draco_mesh_compression bufferView " + std::to_string(view_index) + " out of range");
  }
  const tinygltf::BufferView& view = c.model.bufferViews[static_cast<std::size_t>(view_index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= c.model.buffers.size()) {
    throw c.error("Draco bufferView names a missing buffer");
  }
  const auto& buf = c.model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset) {
    throw c.error("Draco bufferView runs past its buffer");
  }
  auto id_of = [&](const char* key) {
    const tinygltf::Value& v = atts.Get(key);
    return v.IsInt() ? v.Get<int>() : -1;
  };
  const int pos_id = id_of("POSITION");
  if (pos_id < 0) throw c.error("KHR_draco_mesh_compression has no POSITION attribute");
  int batch_id = -1;
  for (const char* key : kBatchNames) if (batch_id < 0) batch_id = id_of(key);
  DracoPrimitive d = decode_draco_primitive(buf.data() + view.byteOffset, view.byteLength, pos_id, batch_id, c.name);
  PrimitiveGeometry g{std::move(d.positions), {}, std::move(d.batch_id)};
  // Draco decodes to triangle lists; the primitive's mode says how to read them (strips are not Draco-encoded).
  if (prim.mode == TINYGLTF_MODE_TRIANGLES) g.triangles = std::move(d.triangles);
  return g;
}

}  // namespace

PrimitiveGeometry read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                 std::size_t mesh_index, const std::string& name) {
  const Ctx c{model, name, "mesh " + std::to_string(mesh_index) + ": "};
  const int mode = prim.mode;
  if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
    throw c.error("primitive mode " + std::to_string(mode) + " invalid");
  }
  if (mode < TINYGLTF_MODE_TRIANGLES) return {};  // points and lines carry no surface
  auto draco = prim.extensions.find("KHR_draco_mesh_compression");
  if (draco != prim.extensions.end()) return read_draco(c, prim, draco->second);

  auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) throw c.error("primitive has no POSITION attribute");
  PrimitiveGeometry g;
  const std::vector<double> xyz = read_accessor(c, pos_it->second, 3, "POSITION");
  g.positions.reserve(xyz.size() / 3);
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) g.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  for (const Eigen::Vector3d& p : g.positions) {
    if (!p.allFinite()) throw c.error("POSITION holds a non-finite value");
  }
  for (const char* key : kBatchNames) {
    auto it = prim.attributes.find(key);
    if (it == prim.attributes.end()) continue;
    const std::vector<double> ids = read_accessor(c, it->second, 1, key);
    if (ids.size() != g.positions.size()) throw c.error(std::string(key) + " count differs from POSITION count");
    for (double v : ids) {
      if (!(v >= 0.0 && v < 4.0e9)) throw c.error(std::string(key) + " holds an invalid batch id");
      g.batch_id.push_back(static_cast<std::uint32_t>(std::lround(v)));
    }
    break;
  }
  std::vector<int> idx;
  if (prim.indices >= 0) {
    const tinygltf::Accessor* acc = static_cast<std::size_t>(prim.indices) < model.accessors.size()
                                        ? &model.accessors[static_cast<std::size_t>(prim.indices)] : nullptr;
    if (acc != nullptr && acc->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        acc->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        acc->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      throw c.error("index accessor " + std::to_string(prim.indices) + " is not an unsigned integer type");
    }
    const std::vector<double> raw = read_accessor(c, prim.indices, 1, "index");
    idx.reserve(raw.size());
    for (double v : raw) idx.push_back(v < 2.0e9 ? static_cast<int>(v) : -1);
  } else {
    idx.resize(g.positions.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  }
  g.triangles = triangles_of(c, mode, idx, g.positions.size());
  return g;
}

}  // namespace twinslam::twin::detail
