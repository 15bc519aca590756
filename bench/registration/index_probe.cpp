// Why per-tile KD-trees: the measurement behind the twin index's design (services/registration/README.md). On the
// 150 m window of tiles around each benchmark keyframe, the same queries (the keyframe's landmarks, radius 1 m: the
// gate after a few ICP iterations) against TwinTileIndex (a FLANN KD-tree per tile) and against a voxel hash of 1 m
// cells (KISS-ICP's structure: a point's 27 neighbouring cells are scanned, exact for radius <= the cell size).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "keyframes.hpp"
#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration::bench {
namespace {

using Clock = std::chrono::steady_clock;
double ms(Clock::time_point a) { return std::chrono::duration<double, std::milli>(Clock::now() - a).count(); }

struct VoxelHash {
  double cell = 1.0;
  std::vector<Eigen::Vector3d> p;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  static std::uint64_t key(long x, long y, long z) {
    return (static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) |
           static_cast<std::uint64_t>(z & 0x1FFFFF);
  }
  void add(const std::vector<Eigen::Vector3d>& pts) {
    for (const auto& q : pts) {
      cells[key(std::lround(std::floor(q.x() / cell)), std::lround(std::floor(q.y() / cell)),
                std::lround(std::floor(q.z() / cell)))]
          .push_back(static_cast<std::uint32_t>(p.size()));
      p.push_back(q);
    }
  }
  double nearest(const Eigen::Vector3d& q, double r) const {
    const long cx = std::lround(std::floor(q.x() / cell)), cy = std::lround(std::floor(q.y() / cell)),
               cz = std::lround(std::floor(q.z() / cell));
    double best = r * r;
    for (long x = cx - 1; x <= cx + 1; ++x)
      for (long y = cy - 1; y <= cy + 1; ++y)
        for (long z = cz - 1; z <= cz + 1; ++z) {
          const auto it = cells.find(key(x, y, z));
          if (it == cells.end()) continue;
          for (std::uint32_t i : it->second) best = std::min(best, (p[i] - q).squaredNorm());
        }
    return std::sqrt(best);
  }
};

}  // namespace

// Prints: per-tile build [ms] KD-tree, voxel hash; query [us/point] KD-tree, voxel hash; found fraction (both equal).
int serve_probe(const std::string& dir, int n) {
  const std::vector<Keyframe> kfs = read_keyframes(dir + "/keyframes.bin");
  const twin::TwinIndex store = twin::read_twin_index(dir + "/twin");
  double kd_build = 0, vh_build = 0, kd_query = 0, vh_query = 0, tiles = 0, queries = 0, found = 0, mismatch = 0;
  for (int i = 0; i < n && !kfs.empty(); ++i) {
    const Keyframe& k = kfs[static_cast<std::size_t>(i) * kfs.size() / static_cast<std::size_t>(n)];
    const Eigen::Vector3d c = k.drift * k.p_WB_true;
    std::vector<twin::Tile> loaded;
    for (const auto& key : tiles_in_window(store, c, 150.0))
      loaded.push_back(twin::load_tile(dir + "/twin", store, key));
    TwinTileIndex index(store.tile_size_m);
    VoxelHash hash;
    auto t0 = Clock::now();
    for (const auto& t : loaded) index.add_tile(t.info.key, t.points_W.p_W, t.points_W.n_W);
    kd_build += ms(t0);
    t0 = Clock::now();
    for (const auto& t : loaded) hash.add(t.points_W.p_W);
    vh_build += ms(t0);
    tiles += static_cast<double>(loaded.size());
    std::vector<double> a, b;
    t0 = Clock::now();
    for (const auto& q : k.p_guess_W) {
      const auto m = index.nearest(q, 1.0);
      a.push_back(m ? m->distance_m : 1.0);
    }
    kd_query += ms(t0);
    t0 = Clock::now();
    for (const auto& q : k.p_guess_W) b.push_back(hash.nearest(q, 1.0));
    vh_query += ms(t0);
    for (std::size_t j = 0; j < a.size(); ++j) {
      found += a[j] < 1.0;
      mismatch += std::abs(a[j] - b[j]) > 1e-4;
    }
    queries += static_cast<double>(a.size());
  }
  std::printf("%.3f %.3f %.3f %.3f %.3f %.0f\n", kd_build / tiles, vh_build / tiles, 1e3 * kd_query / queries,
              1e3 * vh_query / queries, found / queries, mismatch);
  return 0;
}

}  // namespace twinslam::registration::bench
