// PLY: ascii / binary round trips, normals, the simulator's twin PLY, general headers, malformed files.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>

#include "twin_test_utils.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/ply.hpp"

using namespace twinslam::twin;
using twin_test::expect_input_error;
using twin_test::Scratch;
using twin_test::write_text;

namespace {

Mesh two_triangles() {
  Mesh m;
  m.p_W = {{0, 0, 0}, {10.25, 0, 0}, {10.25, 20.5, 3}, {-1234567.125, 7654321.5, 0.001}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

void expect_same(const Mesh& a, const Mesh& b, double tol) {
  ASSERT_EQ(a.p_W.size(), b.p_W.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  ASSERT_EQ(a.n_W.size(), b.n_W.size());
  for (std::size_t i = 0; i < a.p_W.size(); ++i) EXPECT_LE((a.p_W[i] - b.p_W[i]).norm(), tol) << i;
  for (std::size_t i = 0; i < a.n_W.size(); ++i) EXPECT_LE((a.n_W[i] - b.n_W[i]).norm(), 1e-6) << i;
  for (std::size_t i = 0; i < a.triangles.size(); ++i) EXPECT_EQ(a.triangles[i], b.triangles[i]) << i;
}

template <typename T>
void put_le(std::ostream& out, T v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

}  // namespace

TEST(Ply, RoundTripsAsciiAndBothBinaryByteOrders) {
  Scratch tmp;
  const Mesh mesh = two_triangles();
  for (PlyFormat f : {PlyFormat::kAscii, PlyFormat::kBinaryLittleEndian, PlyFormat::kBinaryBigEndian}) {
    const char* name = f == PlyFormat::kAscii ? "a.ply" : f == PlyFormat::kBinaryLittleEndian ? "le.ply" : "be.ply";
    const std::string path = (tmp / name).string();
    write_ply(path, mesh, f, GeoOrigin{52.0, 4.3, 12.5});
    const PlyFile back = read_ply(path);
    expect_same(mesh, back.mesh, 0.0);  // doubles written with 17 digits: exact in ascii too
    ASSERT_TRUE(back.origin.has_value());
    EXPECT_EQ(back.origin->lat_deg, 52.0);
    EXPECT_EQ(back.origin->alt_m, 12.5);
  }
}

TEST(Ply, PointSetWithNormalsRoundTripsAndLoadsAsPointsWithNormals) {
  Scratch tmp;
  Mesh points;
  points.p_W = {{1, 2, 3}, {4, 5, 6}, {-7, 8.5, 9}};
  points.n_W = {{0, 0, 1}, {1, 0, 0}, Eigen::Vector3d(1, 1, 0).normalized()};
  for (PlyFormat f : {PlyFormat::kAscii, PlyFormat::kBinaryLittleEndian}) {
    const std::string path = (tmp / "points.ply").string();
    write_ply(path, points, f);
    LoadOptions options;
    const Mesh loaded = load_twin_source(path, options);  // no origin comment, no --crs: already in W
    expect_same(points, loaded, 0.0);
    EXPECT_EQ(loaded.num_triangles(), 0u);
  }
}

TEST(Ply, ReadsTheSimulatorsTwinFormat) {
  // Byte for byte what tools/sim/world/src/ply.cpp writes: doubles, per face building_id and kind, origin comment.
  Scratch tmp;
  const std::string path = (tmp / "twin.ply").string();
  {
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\n"
        << "comment twinslam mesh; W = East-North-Up [m] at the origin below (WGS84 lat lon [deg], alt [m])\n"
        << "comment twinslam_origin 47.376899999999999 8.5417000000000005 408\n"
        << "comment kind: 0 ground, 1 facade, 2 roof, 3 detail\n"
        << "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
        << "element face 2\nproperty list uchar int vertex_indices\nproperty int building_id\nproperty uchar kind\n"
        << "end_header\n";
    const double xyz[4][3] = {{0, 0, 0}, {5, 0, 0}, {5, 5, 12}, {0, 5, 12}};
    for (const auto& p : xyz)
      for (double c : p) put_le(out, c);
    const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < 2; ++f) {
      put_le<std::uint8_t>(out, 3);
      for (int k = 0; k < 3; ++k) put_le<std::int32_t>(out, faces[f][k]);
      put_le<std::int32_t>(out, 17);
      put_le<std::uint8_t>(out, 1);
    }
  }
  const PlyFile ply = read_ply(path);
  ASSERT_EQ(ply.mesh.num_vertices(), 4u);
  ASSERT_EQ(ply.mesh.num_triangles(), 2u);
  EXPECT_EQ(ply.mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(ply.mesh.p_W[2], Eigen::Vector3d(5, 5, 12));
  ASSERT_TRUE(ply.origin.has_value());
  EXPECT_DOUBLE_EQ(ply.origin->lat_deg, 47.3769);
  EXPECT_DOUBLE_EQ(ply.origin->lon_deg, 8.5417);

  // Loaded at the same origin it stays put; at an origin 100 m further east the twin moves 100 m west.
  LoadOptions same;
  same.origin = *ply.origin;
  EXPECT_EQ(load_twin_source(path, same).p_W[2], Eigen::Vector3d(5, 5, 12));
  LoadOptions east;
  east.origin = *ply.origin;
  const EnuFrame w(*ply.origin);
  const Eigen::Vector3d lla_east = w.to_lla({100, 0, 0});
  east.origin = {lla_east.x(), lla_east.y(), lla_east.z()};
  const Mesh moved = load_twin_source(path, east);
  EXPECT_LT((moved.p_W[0] - Eigen::Vector3d(-100, 0, 0)).norm(), 0.01);  // W's axes turn by 100 m / R: mm here
  EXPECT_LT((moved.p_W[2] - moved.p_W[0] - Eigen::Vector3d(5, 5, 12)).norm(), 0.001);
}

TEST(Ply, GeneralHeadersFloatsPolygonsOtherPropertiesAndElements) {
  Scratch tmp;
  const std::string path = write_text(tmp / "general.ply",
                                      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info x\r\n"
                                      "element vertex 5\r\nproperty float x\r\nproperty uchar red\r\nproperty float y\r\n"
                                      "property float z\r\nproperty list uchar float extra\r\n"
                                      "element face 1\r\nproperty int flags\r\nproperty list int uint vertex_index\r\n"
                                      "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
                                      "0 255 0 0 2 9 9\n1 0 0 0 0\n1 0 1 0 1 7\n0.5 0 1.5 0 0\n0 0 1 0 0\n"
                                      "3 5 0 1 2 3 4\n0 1\n");
  const Mesh m = read_ply(path).mesh;
  ASSERT_EQ(m.num_vertices(), 5u);
  EXPECT_EQ(m.p_W[3], Eigen::Vector3d(0.5, 1.5, 0));
  ASSERT_EQ(m.num_triangles(), 3u);  // the pentagon, fanned from its first vertex
  EXPECT_EQ(m.triangles[2], Eigen::Vector3i(0, 3, 4));
  EXPECT_NEAR(m.total_area(), 1.0 + 0.25, 1e-12);  // unit square + the gable triangle on top
}

TEST(Ply, MalformedFilesAreInputErrorsNamingFileAndReason) {
  Scratch tmp;
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\n"
                             "property double y\nproperty double z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
  auto body = [](int bad_index, double z, std::size_t cut) {
    std::string b;
    auto add = [&b](const void* p, std::size_t n) { b.append(static_cast<const char*>(p), n); };
    for (int i = 0; i < 3; ++i) {
      const double p[3] = {double(i), double(i * i), i == 2 ? z : 0.0};
      add(p, sizeof p);
    }
    const std::uint8_t n = 3;
    const std::int32_t idx[3] = {0, 1, bad_index};
    add(&n, 1);
    add(idx, sizeof idx);
    b.resize(b.size() - cut);
    return b;
  };
  const std::string ok = write_text(tmp / "ok.ply", header + body(2, 1.0, 0));
  EXPECT_EQ(read_ply(ok).mesh.num_triangles(), 1u);
  const std::string trunc = write_text(tmp / "truncated.ply", header + body(2, 1.0, 5));
  expect_input_error([&] { read_ply(trunc); }, trunc, "truncated");
  const std::string range = write_text(tmp / "range.ply", header + body(3, 1.0, 0));
  expect_input_error([&] { read_ply(range); }, range, "out of range");
  const std::string nan = write_text(tmp / "nan.ply", header + body(2, std::nan(""), 0));
  expect_input_error([&] { read_ply(nan); }, nan, "non-finite");
  const std::string not_ply = write_text(tmp / "notply.ply", "solid cube\n");
  expect_input_error([&] { read_ply(not_ply); }, not_ply, "not a PLY file");
  const std::string no_end = write_text(tmp / "noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n");
  expect_input_error([&] { read_ply(no_end); }, no_end, "end_header");
  const std::string bad_type =
      write_text(tmp / "badtype.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n");
  expect_input_error([&] { read_ply(bad_type); }, bad_type, "unknown property type");
  const std::string no_z = write_text(tmp / "noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                                       "property float y\nend_header\n1 2\n");
  expect_input_error([&] { read_ply(no_z); }, no_z, "lacks x, y or z");
  const std::string huge = write_text(tmp / "huge.ply", "ply\nformat binary_little_endian 1.0\n"
                                                        "element vertex 4000000000\nproperty float x\nproperty float y\n"
                                                        "property float z\nend_header\n");
  expect_input_error([&] { read_ply(huge); }, huge, "truncated");
  const std::string text = write_text(tmp / "word.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                                        "property float y\nproperty float z\nend_header\n1 two 3\n");
  expect_input_error([&] { read_ply(text); }, text, "non-number");
  // Through the dispatcher too, with an unknown CRS: the reason names the CRS and the file.
  LoadOptions options;
  options.crs = "EPSG:999999";
  expect_input_error([&] { load_twin_source(ok, options); }, ok, "EPSG:999999");
}

TEST(Ply, EveryTruncationOfAValidFileIsAnInputErrorNeverACrash) {
  Scratch tmp;
  Mesh mesh = two_triangles();
  mesh.n_W.assign(mesh.p_W.size(), Eigen::Vector3d::UnitZ());
  for (PlyFormat f : {PlyFormat::kAscii, PlyFormat::kBinaryBigEndian}) {
    const std::string full_path = (tmp / "full.ply").string();
    write_ply(full_path, mesh, f);
    std::ifstream in(full_path, std::ios::binary);
    const std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t errors = 0;
    for (std::size_t cut = 0; cut < full.size(); ++cut) {
      const std::string path = write_text(tmp / "cut.ply", full.substr(0, cut));
      try {
        read_ply(path);
      } catch (const twinslam::InputError& e) {
        ++errors;
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      }
    }
    // Ascii may lose only the final newline and still be whole; binary loses bytes on every cut.
    EXPECT_GE(errors, full.size() - (f == PlyFormat::kAscii ? 1 : 0));
  }
}
