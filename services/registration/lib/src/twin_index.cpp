// Per-tile KD-trees (KdTree3f: FLANN's KD-tree, see kdtree.hpp).
#include "twinslam/registration/twin_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kdtree.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::registration {

// Points are stored as float relative to the tile's south-west corner: float32 in W would lose ~2 mm at 30 km from
// the twin's origin, relative to the corner the step is < 4 um over a tile.
struct TwinTileIndex::Tile {
  Eigen::Vector3d origin_W = Eigen::Vector3d::Zero();
  Eigen::AlignedBox3d bounds_W;  // of the tile's points (empty box for an empty tile)
  KdTree3f tree{{}};             // points relative to origin_W
  std::vector<Eigen::Vector3f> normals;
  std::size_t size() const { return normals.size(); }
};

struct TwinTileIndex::Best {
  double distance_sq = std::numeric_limits<double>::infinity();
  twin::TileKey key{};
  std::optional<TwinMatch> match;
};

namespace {

void check_tile(const twin::TileKey& key, const std::vector<Eigen::Vector3d>& points_W,
                const std::vector<Eigen::Vector3d>& normals_W) {
  const std::string what = "twin tile " + key.str() + ": ";
  if (points_W.size() != normals_W.size()) {
    throw InputError(what + std::to_string(points_W.size()) + " points but " + std::to_string(normals_W.size()) +
                     " normals");
  }
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    if (!points_W[i].allFinite()) throw InputError(what + "point " + std::to_string(i) + " is not finite");
    if (!normals_W[i].allFinite() || std::abs(normals_W[i].norm() - 1.0) > 1e-3) {
      throw InputError(what + "normal " + std::to_string(i) + " is not a unit vector");
    }
  }
}

// Squared distance from p to the box (0 inside).
double box_distance_sq(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = (box.min() - p).cwiseMax(p - box.max()).cwiseMax(0.0);
  return d.squaredNorm();
}

}  // namespace

TwinTileIndex::TwinTileIndex(double tile_size_m) : tile_size_m_(tile_size_m) {
  if (!std::isfinite(tile_size_m) || tile_size_m <= 0.0) {
    throw InputError("twin index: tile size must be > 0 m, got " + std::to_string(tile_size_m));
  }
}
TwinTileIndex::~TwinTileIndex() = default;
TwinTileIndex::TwinTileIndex(TwinTileIndex&&) noexcept = default;
TwinTileIndex& TwinTileIndex::operator=(TwinTileIndex&&) noexcept = default;

void TwinTileIndex::add_tile(const twin::TileKey& key, const std::vector<Eigen::Vector3d>& points_W,
                             const std::vector<Eigen::Vector3d>& normals_W) {
  check_tile(key, points_W, normals_W);
  auto tile = std::make_unique<Tile>();
  tile->origin_W = twin::tile_origin_W(key, tile_size_m_);
  std::vector<float> xyz;
  xyz.reserve(3 * points_W.size());
  tile->normals.reserve(points_W.size());
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    const Eigen::Vector3f p = (points_W[i] - tile->origin_W).cast<float>();
    xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    tile->normals.push_back(normals_W[i].normalized().cast<float>());
    tile->bounds_W.extend(points_W[i]);
  }
  tile->tree = KdTree3f(std::move(xyz));
  if (!points_W.empty()) {
    // How far the points reach outside the tile's square (never shrinks: removing a tile keeps a safe bound).
    const Eigen::Vector2d lo = tile->origin_W.head<2>(), hi = lo + Eigen::Vector2d::Constant(tile_size_m_);
    const Eigen::Vector2d out = (lo - tile->bounds_W.min().head<2>()).cwiseMax(tile->bounds_W.max().head<2>() - hi);
    spill_m_ = std::max(spill_m_, out.maxCoeff());
  }
  tiles_[key] = std::move(tile);
}

bool TwinTileIndex::remove_tile(const twin::TileKey& key) { return tiles_.erase(key) > 0; }
bool TwinTileIndex::contains(const twin::TileKey& key) const { return tiles_.count(key) > 0; }

std::vector<twin::TileKey> TwinTileIndex::keys() const {
  std::vector<twin::TileKey> k;
  for (const auto& [key, tile] : tiles_) k.push_back(key);
  return k;
}

std::size_t TwinTileIndex::tile_count() const { return tiles_.size(); }

std::size_t TwinTileIndex::point_count() const {
  std::size_t n = 0;
  for (const auto& [key, tile] : tiles_) n += tile->size();
  return n;
}

std::size_t TwinTileIndex::memory_bytes() const {
  // Point (12 B) and the tree's reordered copy (12 B), normal (12 B), the tree's index (8 B per point) and nodes
  // (~ one of ~40 B per 5 points).
  std::size_t bytes = 0;
  for (const auto& [key, tile] : tiles_) bytes += sizeof(Tile) + tile->size() * (12 + 12 + 12 + 8 + 8);
  return bytes;
}

std::optional<TwinMatch> TwinTileIndex::nearest(const Eigen::Vector3d& p_W, double max_dist_m) const {
  if (!p_W.allFinite() || !(max_dist_m > 0.0)) return std::nullopt;
  // Beyond the world no tile can be; and the tile numbers below must fit an int.
  if (p_W.head<2>().cwiseAbs().maxCoeff() > kMaxWorldCoordinate_m) return std::nullopt;
  max_dist_m = std::min(max_dist_m, kMaxWorldCoordinate_m);
  const double max_sq = max_dist_m * max_dist_m;
  Best best;
  // The tile holding the query first: its nearest point usually bounds the search so tightly that no other tile
  // is in reach. Ties go to the lower tile key whatever the order of the search.
  const twin::TileKey home{static_cast<int>(std::floor(p_W.x() / tile_size_m_)),
                           static_cast<int>(std::floor(p_W.y() / tile_size_m_))};
  if (const auto it = tiles_.find(home); it != tiles_.end()) search_tile(home, *it->second, p_W, max_sq, best);
  // Other candidate tiles by grid cell: a tile's points may spill outside its square (by spill_m_ at most), the
  // exact test is each tile's bounding box.
  const double reach = std::min(max_dist_m, std::sqrt(best.distance_sq)) + spill_m_;
  const int ix0 = static_cast<int>(std::floor((p_W.x() - reach) / tile_size_m_));
  const int ix1 = static_cast<int>(std::floor((p_W.x() + reach) / tile_size_m_));
  const int iy0 = static_cast<int>(std::floor((p_W.y() - reach) / tile_size_m_));
  const int iy1 = static_cast<int>(std::floor((p_W.y() + reach) / tile_size_m_));
  if (ix0 == ix1 && iy0 == iy1) return best.match;  // only the home tile is in reach
  for (int ix = ix0; ix <= ix1; ++ix) {
    for (auto it = tiles_.lower_bound({ix, iy0}); it != tiles_.end() && it->first <= twin::TileKey{ix, iy1}; ++it) {
      if (it->first != home) search_tile(it->first, *it->second, p_W, max_sq, best);
    }
  }
  return best.match;
}

void TwinTileIndex::search_tile(const twin::TileKey& key, const Tile& t, const Eigen::Vector3d& p_W, double max_sq,
                                Best& best) {
  if (t.tree.empty()) return;
  const double bound_sq = std::min(max_sq, best.distance_sq);
  if (box_distance_sq(t.bounds_W, p_W) > bound_sq) return;
  const Eigen::Vector3f q = (p_W - t.origin_W).cast<float>();
  // Float radius slack of 1e-4 m (squared below, relative 1e-6 for roundoff); the exact test is in double below.
  const double r = std::sqrt(bound_sq) + 1e-4;
  float found_sq = 0.0f;
  const std::size_t i = t.tree.nearest_within(q.data(), static_cast<float>(r * r * (1.0 + 1e-6)), found_sq);
  if (i == KdTree3f::kNone) return;
  const float* c = t.tree.point(i);
  const Eigen::Vector3d b_W = t.origin_W + Eigen::Vector3d(c[0], c[1], c[2]);
  const double d_sq = (b_W - p_W).squaredNorm();
  if (d_sq > max_sq || d_sq > best.distance_sq || (d_sq == best.distance_sq && !(key < best.key))) return;
  best.distance_sq = d_sq;
  best.key = key;
  best.match = TwinMatch{b_W, t.normals[i].cast<double>(), std::sqrt(d_sq)};
}

std::vector<std::optional<TwinMatch>> TwinTileIndex::nearest_batch(const std::vector<Eigen::Vector3d>& p_W,
                                                                   double max_dist_m) const {
  std::vector<std::optional<TwinMatch>> out;
  out.reserve(p_W.size());
  for (const Eigen::Vector3d& p : p_W) out.push_back(nearest(p, max_dist_m));
  return out;
}

}  // namespace twinslam::registration
