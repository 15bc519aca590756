// glTF 2.0 -> Mesh in the y-up model frame (see gltf.hpp). The one translation unit with tinygltf's implementation.
// Images are neither decoded nor loaded (no stb): only geometry matters for the twin. tinygltf's Draco support is
// NOT enabled: its decoder path dereferences unchecked accessor / bufferView / Draco attribute indices (a crafted
// file crashes it) and drops decode failures silently. KHR_draco_mesh_compression is decoded in gltf_draco.cpp with
// every index checked; gltf_prepare.cpp only hides the Draco primitives' index accessors from tinygltf's parser.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>

#include "glb.hpp"
#include "gltf_accessor.hpp"
#include "gltf_draco.hpp"
#include "gltf_prepare.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/gltf.hpp"

namespace twinslam::twin {
namespace {

bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;  // geometry only: textures are not part of the twin
}

// Local transform of a node: its matrix (column-major) or T * R * S.
Eigen::Matrix4d node_matrix(const tinygltf::Node& node, const std::string& name, std::size_t index) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  auto bad = [&](const std::string& what) {
    return InputError(where(name, 0, "node " + std::to_string(index) + " " + what));
  };
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) throw bad("matrix has " + std::to_string(node.matrix.size()) + " values, not 16");
    for (int i = 0; i < 16; ++i) M(i % 4, i / 4) = node.matrix[static_cast<std::size_t>(i)];
  } else {
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) throw bad("translation is not 3 values");
      T.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) throw bad("rotation is not a quaternion (4 values)");
      // glTF stores (x, y, z, w).
      Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      if (!(q.norm() > 1e-9)) throw bad("rotation quaternion is zero");
      T.rotate(q.normalized().toRotationMatrix());
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) throw bad("scale is not 3 values");
      T.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
    }
    M = T.matrix();
  }
  if (!M.allFinite()) throw bad("transform is not finite");
  return M;
}

struct Walker {
  const tinygltf::Model& model;
  const std::string& name;
  GltfContent out;
  bool has_batch = false;
  std::vector<bool> on_path;  // nodes on the current root-to-node path: a cycle would recurse forever

  void add_primitive(const tinygltf::Primitive& prim, std::size_t mesh_index, const Eigen::Matrix4d& M) {
    detail::PrimitiveGeometry geo = detail::read_primitive(model, prim, mesh_index, name);
    if (geo.triangles.empty()) return;  // points / lines, or an empty primitive
    const int base = static_cast<int>(out.mesh.p_W.size());
    if (out.mesh.p_W.size() + geo.positions.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw InputError(where(name, 0, "more vertices than a Mesh can index"));
    }
    for (const Eigen::Vector3d& p : geo.positions) out.mesh.p_W.push_back((M * p.homogeneous()).head<3>());
    for (const Eigen::Vector3i& t : geo.triangles) out.mesh.triangles.push_back(t.array() + base);
    // Batch ids stay aligned with vertices; primitives without them get the "no feature" id.
    if (!geo.batch_id.empty() && !has_batch) {
      out.batch_id.assign(static_cast<std::size_t>(base), std::numeric_limits<std::uint32_t>::max());
      has_batch = true;
    }
    if (has_batch) {
      if (geo.batch_id.empty()) geo.batch_id.assign(geo.positions.size(), std::numeric_limits<std::uint32_t>::max());
      out.batch_id.insert(out.batch_id.end(), geo.batch_id.begin(), geo.batch_id.end());
    }
  }

  void visit(int node_index, const Eigen::Matrix4d& parent) {
    if (node_index < 0 || static_cast<std::size_t>(node_index) >= model.nodes.size()) {
      throw InputError(where(name, 0, "node index " + std::to_string(node_index) + " out of range"));
    }
    const auto n = static_cast<std::size_t>(node_index);
    if (on_path[n]) throw InputError(where(name, 0, "node hierarchy has a cycle through node " + std::to_string(n)));
    on_path[n] = true;
    const tinygltf::Node& node = model.nodes[n];
    const Eigen::Matrix4d M = parent * node_matrix(node, name, n);
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model.meshes.size()) {
        throw InputError(where(name, 0, "node " + std::to_string(n) + " mesh index out of range"));
      }
      for (const tinygltf::Primitive& prim : model.meshes[static_cast<std::size_t>(node.mesh)].primitives) {
        add_primitive(prim, static_cast<std::size_t>(node.mesh), M);
      }
    }
    for (int child : node.children) visit(child, M);
    on_path[n] = false;
  }
};

// Roots to draw: the default scene (or the first), or with no scene every node that is nobody's child.
std::vector<int> root_nodes(const tinygltf::Model& model, const std::string& name) {
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(s) >= model.scenes.size()) {
      throw InputError(where(name, 0, "default scene out of range"));
    }
    return model.scenes[static_cast<std::size_t>(s)].nodes;
  }
  std::vector<bool> is_child(model.nodes.size(), false);
  for (const auto& node : model.nodes) {
    for (int c : node.children) {
      if (c >= 0 && static_cast<std::size_t>(c) < is_child.size()) is_child[static_cast<std::size_t>(c)] = true;
    }
  }
  std::vector<int> roots;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (!is_child[i]) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

// CESIUM_RTC: {"center": [x, y, z]} in the z-up (ECEF) frame, added before the tile transform.
Eigen::Vector3d cesium_rtc_y_up(const tinygltf::Model& model, const std::string& name) {
  auto it = model.extensions.find("CESIUM_RTC");
  if (it == model.extensions.end()) return Eigen::Vector3d::Zero();
  const tinygltf::Value& center = it->second.Get("center");
  if (!center.IsArray() || center.ArrayLen() != 3) {
    throw InputError(where(name, 0, "CESIUM_RTC center is not 3 numbers"));
  }
  Eigen::Vector3d c;
  for (int i = 0; i < 3; ++i) {
    const tinygltf::Value& v = center.Get(i);
    if (!v.IsNumber()) throw InputError(where(name, 0, "CESIUM_RTC center is not 3 numbers"));
    c[i] = v.GetNumberAsDouble();
  }
  return gltf_z_up_to_y_up(c);
}

}  // namespace

GltfContent load_gltf_content(const std::uint8_t* data, std::size_t size, const std::string& name,
                              const std::string& base_dir) {
  if (data == nullptr || size == 0) throw InputError(where(name, 0, "empty glTF"));
  if (size > std::numeric_limits<unsigned int>::max()) throw InputError(where(name, 0, "glTF larger than 4 GiB"));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string err;
  std::string warn;
  bool ok = false;
  // tinygltf reports most problems through `err`, but some malformed files make it throw (std::vector::at in
  // ParseBuffer, found by byte-flipping a GLB): those are bad input too.
  try {
    if (detail::looks_like_glb(data, size)) {
      const detail::GlbChunks chunks = detail::check_glb(data, size, name);
      const auto prepared = detail::drop_draco_indices(data, size, &chunks);
      const std::uint8_t* bytes = prepared ? prepared->data() : data;
      const std::size_t length = prepared ? prepared->size() : chunks.length;
      if (length > std::numeric_limits<unsigned int>::max()) throw InputError(where(name, 0, "glTF larger than 4 GiB"));
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes, static_cast<unsigned int>(length), base_dir);
    } else {
      std::size_t first = 0;
      while (first < size && std::isspace(data[first]) != 0) ++first;
      if (first == size || data[first] != '{') {
        throw InputError(where(name, 0, "neither binary glTF (magic 'glTF') nor JSON glTF"));
      }
      const auto prepared = detail::drop_draco_indices(data, size, nullptr);
      const std::uint8_t* bytes = prepared ? prepared->data() : data;
      const std::size_t length = prepared ? prepared->size() : size;
      if (length > std::numeric_limits<unsigned int>::max()) throw InputError(where(name, 0, "glTF larger than 4 GiB"));
      ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes),
                                      static_cast<unsigned int>(length), base_dir);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(where(name, 0, std::string("glTF: malformed (") + e.what() + ")"));
  }
  if (!ok) {
    std::string reason = err.empty() ? "not a valid glTF" : err;
    for (char& c : reason) if (c == '\n') c = ' ';
    while (!reason.empty() && reason.back() == ' ') reason.pop_back();
    throw InputError(where(name, 0, "glTF: " + reason));
  }
  Walker walker{model, name, {}, false, std::vector<bool>(model.nodes.size(), false)};
  const Eigen::Vector3d rtc = cesium_rtc_y_up(model, name);
  Eigen::Matrix4d T_rtc = Eigen::Matrix4d::Identity();
  T_rtc.topRightCorner<3, 1>() = rtc;
  for (int root : root_nodes(model, name)) walker.visit(root, T_rtc);
  walker.out.cesium_rtc = model.extensions.count("CESIUM_RTC") > 0;
  return std::move(walker.out);
}

Mesh load_gltf_memory(const std::uint8_t* data, std::size_t size, const std::string& name_for_errors) {
  return load_gltf_content(data, size, name_for_errors).mesh;
}

std::vector<std::uint8_t> read_binary_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where(path, 0, "cannot open file"));
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(where(path, 0, "read error"));
  return bytes;
}

Mesh load_gltf_file(const std::string& path) {
  const std::vector<std::uint8_t> bytes = read_binary_file(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return load_gltf_content(bytes.data(), bytes.size(), path, dir.empty() ? "." : dir).mesh;
}

}  // namespace twinslam::twin
