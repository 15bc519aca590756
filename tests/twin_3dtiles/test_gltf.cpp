// glTF 2.0 / GLB loading: Draco decoding, node hierarchy, strips and fans, CESIUM_RTC, and every kind of bad input.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "tiles_test_utils.hpp"
#include "twinslam/twin/gltf.hpp"

using namespace twinslam::twin;
using namespace tiles_test;

namespace {

std::string base64(const std::vector<std::uint8_t>& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t b1 = i + 1 < in.size() ? in[i + 1] : 0;
    const std::uint32_t b2 = i + 2 < in.size() ? in[i + 2] : 0;
    const std::uint32_t n = (static_cast<std::uint32_t>(in[i]) << 16) | (b1 << 8) | b2;
    out += k[(n >> 18) & 63];
    out += k[(n >> 12) & 63];
    out += i + 1 < in.size() ? k[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? k[n & 63] : '=';
  }
  return out;
}

// Four float positions of a unit square in the x-y plane, counter-clockwise seen from +z: in zig-zag order for a
// strip, around the rim for a fan (and for the other modes).
std::vector<std::uint8_t> square_floats(int mode) {
  const float strip[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const float rim[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float* p = mode == 5 ? strip : rim;
  std::vector<std::uint8_t> b(12 * sizeof(float));
  std::memcpy(b.data(), p, b.size());
  return b;
}

// A JSON glTF of the square with one primitive of `mode`, under a parent node translated by (10, 0, 0) whose child is
// scaled by 2; `extra` is spliced into the top-level object (extensions).
std::string square_gltf(int mode, int count, const std::string& extra = "", const std::string& uri = "") {
  const std::string data = uri.empty() ? "data:application/octet-stream;base64," + base64(square_floats(mode)) : uri;
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
         R"("nodes":[{"translation":[10,0,0],"children":[1]},{"scale":[2,2,2],"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":)" + std::to_string(mode) + R"(}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" + std::to_string(count) +
         R"(,"type":"VEC3"}],"bufferViews":[{"buffer":0,"byteLength":48}],)"
         R"("buffers":[{"byteLength":48,"uri":")" + data + "\"}]" + extra + "}";
}

Mesh load_text(const std::string& text, const std::string& name = "square.gltf") {
  return load_gltf_memory(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), name);
}

std::size_t bin_chunk_data(const std::vector<std::uint8_t>& glb) { return 20 + get_u32(glb, 12) + 8; }

}  // namespace

TEST(Gltf, BoxDracoDecodesToTheUnitBox) {
  const Mesh box = load_gltf_file(sample("cesium-tools/BoxDraco.glb"));
  EXPECT_EQ(box.num_triangles(), 12u);
  std::set<std::tuple<double, double, double>> corners;
  for (const Eigen::Vector3d& p : box.p_W) {
    // The root node turns the box -90 deg about X; a cube centred at 0 maps onto itself, corners stay at +-0.5.
    EXPECT_NEAR(std::abs(p.x()), 0.5, 1e-6);
    EXPECT_NEAR(std::abs(p.y()), 0.5, 1e-6);
    EXPECT_NEAR(std::abs(p.z()), 0.5, 1e-6);
    corners.insert({std::round(p.x() * 2), std::round(p.y() * 2), std::round(p.z() * 2)});
  }
  EXPECT_EQ(corners.size(), 8u);
  EXPECT_NEAR(box.total_area(), 6.0, 1e-6);  // 6 unit faces: triangles are the box's, not a garbled index list
}

TEST(Gltf, StripAndFanBecomeTrianglesWithNodeTransformsApplied) {
  const Mesh strip = load_text(square_gltf(5, 4));
  ASSERT_EQ(strip.num_triangles(), 2u);
  const Mesh fan = load_text(square_gltf(6, 4));
  ASSERT_EQ(fan.num_triangles(), 2u);
  for (const Mesh* m : {&strip, &fan}) {
    // parent translation (10, 0, 0) after child scale 2: x in [10, 12], y in [0, 2]; area 4 m^2 (2 x 2 square)
    const Eigen::AlignedBox3d b = m->bounds();
    EXPECT_TRUE(b.min().isApprox(Eigen::Vector3d(10, 0, 0)));
    EXPECT_TRUE(b.max().isApprox(Eigen::Vector3d(12, 2, 0)));
    EXPECT_NEAR(m->total_area(), 4.0, 1e-9);
    // One winding for the whole strip / fan: both normals point the same way (+z for this vertex order).
    EXPECT_NEAR(m->triangle_normal(0).z(), 1.0, 1e-9);
    EXPECT_NEAR(m->triangle_normal(1).z(), 1.0, 1e-9);
  }
  EXPECT_EQ(load_text(square_gltf(0, 4)).num_triangles(), 0u);  // points carry no surface
}

TEST(Gltf, CesiumRtcCenterIsAddedAsAZUpOffset) {
  const std::string rtc = R"(,"extensionsUsed":["CESIUM_RTC"],"extensions":{"CESIUM_RTC":{"center":[100,200,300]}})";
  const Mesh m = load_text(square_gltf(4, 3, rtc));
  ASSERT_EQ(m.num_vertices(), 3u);
  // Model frame stays y-up; turned to z-up the first vertex (10, 0, 0) lands at (10, 0, 0) + center.
  EXPECT_TRUE(gltf_y_up_to_z_up(m.p_W[0]).isApprox(Eigen::Vector3d(110, 200, 300)));
}

TEST(Gltf, BadInputThrowsInputErrorNamingFileAndReason) {
  const std::vector<std::uint8_t> box = bytes_of(sample("cesium-tools/BoxDraco.glb"));
  auto load = [](std::vector<std::uint8_t> b) { return [b] { load_gltf_memory(b.data(), b.size(), "box.glb"); }; };

  std::vector<std::uint8_t> magic = box;
  magic[0] = 'X';
  expect_input_error(load(magic), {"box.glb", "neither binary glTF"});
  std::vector<std::uint8_t> version = box;
  put_u32(version, 4, 1);
  expect_input_error(load(version), {"box.glb", "GLB version 1"});
  std::vector<std::uint8_t> cut(box.begin(), box.begin() + static_cast<long>(box.size() / 2));
  expect_input_error(load(cut), {"box.glb", "exceeds"});
  std::vector<std::uint8_t> chunk = box;
  put_u32(chunk, 12, 1u << 30);
  expect_input_error(load(chunk), {"box.glb", "chunk 0", "runs past"});
  std::vector<std::uint8_t> type = box;
  put_u32(type, 16, 0x004E4942);  // "BIN" where JSON must be
  expect_input_error(load(type), {"box.glb", "first chunk is not JSON"});
  std::vector<std::uint8_t> draco = box;
  const std::size_t bin = bin_chunk_data(box);
  draco[bin] = 'X';  // the Draco stream starts with "DRACO"
  expect_input_error(load(draco), {"box.glb", "Draco decode failure"});

  expect_input_error([] { load_text(square_gltf(4, 400)); }, {"square.gltf", "runs past bufferView"});
  expect_input_error([] { load_text(square_gltf(4, 3, "", "missing.bin")); }, {"square.gltf", "missing.bin"});
  expect_input_error([] { load_text("{\"asset\": "); }, {"square.gltf", "glTF"});
  expect_input_error([] { load_gltf_file("/nonexistent/x.glb"); }, {"/nonexistent/x.glb", "cannot open"});
}

TEST(Gltf, CorruptedDracoBytesNeverCrash) {
  // Flip bytes all over the compressed stream: each load either decodes something or throws InputError.
  const std::vector<std::uint8_t> box = bytes_of(sample("cesium-tools/BoxDraco.glb"));
  const std::size_t bin = bin_chunk_data(box);
  std::mt19937 rng(7);
  int errors = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> b = box;
    for (int k = 0; k < 4; ++k) b[bin + rng() % 130] = static_cast<std::uint8_t>(rng());
    try {
      const Mesh m = load_gltf_memory(b.data(), b.size(), "fuzz.glb");
      for (const Eigen::Vector3i& t : m.triangles) {
        ASSERT_TRUE((t.array() >= 0).all() && (t.array() < static_cast<int>(m.num_vertices())).all());
      }
    } catch (const twinslam::InputError&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 0);  // the corruption is seen at least sometimes
}
