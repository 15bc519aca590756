// Draco round trip of tiles (store.hpp): the issue's acceptance point "decoded tile vertices within the Draco
// quantization error (<= 1 mm at the chosen setting)", for a tile far from the origin, and corrupt bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_meshes.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/store.hpp"
#include "twinslam/twin/tiling.hpp"

namespace twinslam::twin {
namespace {

// Largest distance from a vertex of `a` to its nearest vertex of `b` [m] (brute force: tiles of a few hundred).
double max_nearest(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double worst = 0;
  for (const Eigen::Vector3d& p : a) {
    double best = INFINITY;
    for (const Eigen::Vector3d& q : b) best = std::min(best, (p - q).squaredNorm());
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

// The bound of store.hpp per coordinate, as a 3D distance [m].
double quantization_bound(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin, int bits) {
  const double range = box.sizes().maxCoeff();
  const double far = (box.max() - origin).cwiseAbs().cwiseMax((box.min() - origin).cwiseAbs()).maxCoeff();
  return std::sqrt(3.0) * (range / (2.0 * (std::pow(2.0, bits) - 1.0)) + far * 0x1.0p-24);
}

class TwinDraco : public ::testing::Test {
 protected:
  // A city block 3 km east and north of the origin; its tile (60, 59) of 50 m, with buildings up to 64 m tall.
  void SetUp() override {
    tiles_ = cut_into_tiles(test::box_city(2990.0, 2940.0, 6, 13.0, 12, 5), 50.0);
    key_ = TileKey{60, 59};
    ASSERT_TRUE(tiles_.count(key_));
    tile_ = tiles_.at(key_);
  }
  std::map<TileKey, Mesh> tiles_;
  TileKey key_;
  Mesh tile_;
};

TEST_F(TwinDraco, MeshTileThreeKilometresOutRoundTripsWithinTheQuantizationBound) {
  const StoreConfig config;  // default 20 bits
  const Eigen::Vector3d origin = tile_origin_W(key_, config.tile_size_m);
  const std::vector<std::uint8_t> bytes = encode_mesh(tile_, config, origin);
  const Mesh back = decode_draco(bytes.data(), bytes.size(), "tile.drc");
  ASSERT_EQ(back.num_triangles(), tile_.num_triangles());
  const double bound = quantization_bound(tile_.bounds(), origin, config.position_bits);
  EXPECT_LE(bound, 1e-4);  // 64 m tall content at 20 bits: 0.1 mm, well inside the 1 mm
  EXPECT_LE(max_nearest(back.p_W, tile_.p_W), bound);
  EXPECT_LE(max_nearest(tile_.p_W, back.p_W), bound);
  EXPECT_NEAR(back.total_area(), tile_.total_area(), 1e-5 * tile_.total_area());
  // The file carries its offset: without telling the decoder anything, coordinates come back in W, 3 km out.
  EXPECT_GT(back.bounds().min().x(), 2999.0);
  // Fewer bits, larger but still bounded error: the bound is what the code does, not a lucky margin.
  StoreConfig coarse;
  coarse.position_bits = 11;
  const std::vector<std::uint8_t> coarse_bytes = encode_mesh(tile_, coarse, origin);
  const Mesh coarse_back = decode_draco(coarse_bytes.data(), coarse_bytes.size(), "tile.drc");
  const double coarse_error = max_nearest(tile_.p_W, coarse_back.p_W);
  EXPECT_GT(coarse_error, bound);
  EXPECT_LE(coarse_error, quantization_bound(tile_.bounds(), origin, coarse.position_bits));
  EXPECT_LT(coarse_bytes.size(), bytes.size());
}

TEST_F(TwinDraco, PointsRoundTripWithNormals) {
  const StoreConfig config;
  const Mesh points = sample_points(tile_, config.point_spacing_m, 3);
  ASSERT_GT(points.p_W.size(), 1000u);
  const std::vector<std::uint8_t> bytes = encode_points(points, config);  // default origin: bounds corner, whole m
  const Mesh back = decode_draco(bytes.data(), bytes.size(), "points.drc");
  ASSERT_EQ(back.p_W.size(), points.p_W.size());
  ASSERT_EQ(back.n_W.size(), back.p_W.size());
  EXPECT_TRUE(back.triangles.empty());
  // Draco may reorder points: match each decoded point to the source point nearest to it, then compare normals.
  const double bound = quantization_bound(points.bounds(), points.bounds().min().array().floor().matrix(), 20);
  const std::size_t step = 37;  // a sample of the points keeps the brute-force match fast
  for (std::size_t i = 0; i < back.p_W.size(); i += step) {
    std::size_t best = 0;
    for (std::size_t j = 1; j < points.p_W.size(); ++j) {
      if ((points.p_W[j] - back.p_W[i]).squaredNorm() < (points.p_W[best] - back.p_W[i]).squaredNorm()) best = j;
    }
    EXPECT_LE((points.p_W[best] - back.p_W[i]).norm(), bound);
    EXPECT_GT(points.n_W[best].dot(back.n_W[i]), std::cos(1.0 * M_PI / 180.0));  // 10 normal bits: < 1 deg
  }
}

TEST_F(TwinDraco, CorruptOrTruncatedBytesAreInputErrors) {
  const std::vector<std::uint8_t> bytes = encode_mesh(tile_, StoreConfig{});
  EXPECT_THROW(decode_draco(nullptr, 0, "x.drc"), InputError);
  const std::vector<std::uint8_t> text = {'h', 'e', 'l', 'l', 'o'};
  EXPECT_THROW(decode_draco(text.data(), text.size(), "x.drc"), InputError);
  for (std::size_t n : {std::size_t{4}, std::size_t{10}, bytes.size() / 4, bytes.size() / 2, bytes.size() - 1}) {
    EXPECT_THROW(decode_draco(bytes.data(), n, "x.drc"), InputError) << "truncated to " << n;
  }
  try {
    decode_draco(bytes.data(), 12, "tiles/1_2.mesh.drc");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tiles/1_2.mesh.drc"), std::string::npos) << e.what();
  }
  // Flipped bytes in the payload: Draco may still decode something, but it must never crash or throw anything else.
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<std::uint8_t> bad = bytes;
    for (int k = 0; k < 3; ++k) bad[rng() % bad.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    try {
      const Mesh m = decode_draco(bad.data(), bad.size(), "x.drc");
      for (const Eigen::Vector3i& t : m.triangles) ASSERT_LT(static_cast<std::size_t>(t.maxCoeff()), m.p_W.size());
    } catch (const InputError&) {
    }
  }
}

// Draco sizes its tables from the counts at the head of a bitstream: a few bytes claiming 2^28 faces made it
// allocate 5.6 GB (found by fuzzing). Such counts are refused with the file's name before Draco sees them.
std::vector<std::uint8_t> draco_head(std::uint8_t geometry, std::uint8_t method, std::vector<std::uint8_t> fields) {
  std::vector<std::uint8_t> out = {'D', 'R', 'A', 'C', 'O', 2, 2, geometry, method, 0, 0};
  for (const std::uint8_t b : fields) out.push_back(b);
  out.resize(out.size() + 150, 0x1c);  // some payload, as the fuzzer's input had
  return out;
}

TEST(TwinDracoCounts, CountsTheBytesCannotHoldAreRefusedBeforeDecoding) {
  const std::vector<std::uint8_t> huge = {0xff, 0xff, 0xff, 0x7f};  // varint 2^28 - 1
  const std::vector<std::pair<std::string, std::vector<std::uint8_t>>> cases = {
      // edgebreaker mesh (method 1): traversal 0, vertices 3, faces 2^28 - 1
      {"faces", draco_head(1, 1, {0, 3, huge[0], huge[1], huge[2], huge[3], 0, 1, 0})},
      // edgebreaker mesh: vertices 2^28 - 1, faces 1
      {"vertices", draco_head(1, 1, {0, huge[0], huge[1], huge[2], huge[3], 1, 0, 1, 0})},
      // sequential mesh (method 0): faces 1, points 2^28 - 1
      {"points", draco_head(1, 0, {1, huge[0], huge[1], huge[2], huge[3]})},
      // sequential point cloud (geometry 0, method 0): int32 point count 2^28 - 1
      {"points", draco_head(0, 0, {0xff, 0xff, 0xff, 0x0f})},
  };
  for (const auto& [what, bytes] : cases) {
    try {
      decode_draco(bytes.data(), bytes.size(), "tiles/3_4.mesh.drc");
      ADD_FAILURE() << what << ": decoded";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("tiles/3_4.mesh.drc"), std::string::npos) << message;
      EXPECT_NE(message.find("claims 268435455 " + what), std::string::npos) << message;
    }
  }
  // A KD-tree point cloud older than 2.3 hides a second count in its attribute data: refused by version.
  const std::vector<std::uint8_t> old_kd_tree = draco_head(0, 1, {4, 0, 0, 0});
  try {
    decode_draco(old_kd_tree.data(), old_kd_tree.size(), "tiles/3_4.points.drc");
    ADD_FAILURE() << "an old KD-tree stream decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("KD-tree point cloud bitstream 2.2 (before 2.3) is not supported"),
              std::string::npos)
        << e.what();
  }
}

TEST(TwinDracoEncode, EmptyOrNonFiniteInputIsRejected) {
  EXPECT_THROW(encode_mesh(Mesh{}, StoreConfig{}), InputError);
  EXPECT_THROW(encode_points(Mesh{}, StoreConfig{}), InputError);
  Mesh m;
  m.p_W = {{0, 0, 0}, {1, 0, 0}, {0, INFINITY, 0}};
  m.triangles = {{0, 1, 2}};
  EXPECT_THROW(encode_mesh(m, StoreConfig{}), InputError);
  StoreConfig bad;
  bad.position_bits = 40;
  EXPECT_THROW(bad.validate(), UsageError);
}

}  // namespace
}  // namespace twinslam::twin
