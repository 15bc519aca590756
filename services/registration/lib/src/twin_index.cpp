// Per-tile KD-trees (PCL KdTreeFLANN). The only file of the index that includes PCL (~24 s per translation unit).
#include "twinslam/registration/twin_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "twinslam/core/error.hpp"

namespace twinslam::registration {

// Points are stored as float relative to the tile's south-west corner: float32 in W would lose ~2 mm at 30 km from
// the twin's origin, relative to the corner the step is < 4 um over a tile.
struct TwinTileIndex::Tile {
  Eigen::Vector3d origin_W = Eigen::Vector3d::Zero();
  Eigen::AlignedBox3d bounds_W;  // of the tile's points (empty box for an empty tile)
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
  std::vector<Eigen::Vector3f> normals;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
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
  tile->cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  tile->cloud->reserve(points_W.size());
  tile->normals.reserve(points_W.size());
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    const Eigen::Vector3f p = (points_W[i] - tile->origin_W).cast<float>();
    tile->cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    tile->normals.push_back(normals_W[i].normalized().cast<float>());
    tile->bounds_W.extend(points_W[i]);
  }
  if (!tile->cloud->empty()) tile->tree.setInputCloud(tile->cloud);
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
  for (const auto& [key, tile] : tiles_) n += tile->cloud->size();
  return n;
}

std::size_t TwinTileIndex::memory_bytes() const {
  // Point (16 B as PointXYZ), normal (12 B), FLANN's index (~ one int per point plus nodes of ~15 points).
  std::size_t bytes = 0;
  for (const auto& [key, tile] : tiles_) bytes += sizeof(Tile) + tile->cloud->size() * (16 + 12 + 4 + 8);
  return bytes;
}

std::optional<TwinMatch> TwinTileIndex::nearest(const Eigen::Vector3d& p_W, double max_dist_m) const {
  if (!p_W.allFinite() || !(max_dist_m > 0.0)) return std::nullopt;
  // Candidate tiles by grid cell: a tile's points may spill a little outside its square (triangles cut at the
  // border), so the grid range is widened by one tile and the exact test is the points' bounding box.
  const int ix0 = static_cast<int>(std::floor((p_W.x() - max_dist_m) / tile_size_m_)) - 1;
  const int ix1 = static_cast<int>(std::floor((p_W.x() + max_dist_m) / tile_size_m_)) + 1;
  const int iy0 = static_cast<int>(std::floor((p_W.y() - max_dist_m) / tile_size_m_)) - 1;
  const int iy1 = static_cast<int>(std::floor((p_W.y() + max_dist_m) / tile_size_m_)) + 1;
  const double max_sq = max_dist_m * max_dist_m;
  double best_sq = std::numeric_limits<double>::infinity();
  std::optional<TwinMatch> best;
  for (int ix = ix0; ix <= ix1; ++ix) {
    for (auto it = tiles_.lower_bound({ix, iy0}); it != tiles_.end() && it->first <= twin::TileKey{ix, iy1}; ++it) {
      search_tile(*it->second, p_W, max_sq, best_sq, best);
    }
  }
  return best;
}

void TwinTileIndex::search_tile(const Tile& t, const Eigen::Vector3d& p_W, double max_sq, double& best_sq,
                                std::optional<TwinMatch>& best) {
  if (t.cloud->empty()) return;
  if (box_distance_sq(t.bounds_W, p_W) > std::min(max_sq, best_sq)) return;
  const Eigen::Vector3f q = (p_W - t.origin_W).cast<float>();
  thread_local pcl::Indices idx(1);
  thread_local std::vector<float> dist(1);
  // radiusSearch with max_nn = 1 keeps the closest point within the radius (FLANN KNNRadiusResultSet), pruning by the
  // gate from the start; float radius slack of 1e-4 m, the exact test is in double below.
  if (t.tree.radiusSearch(pcl::PointXYZ(q.x(), q.y(), q.z()), std::sqrt(max_sq) + 1e-4, idx, dist, 1) < 1) return;
  const auto i = static_cast<std::size_t>(idx[0]);
  const auto& c = (*t.cloud)[i];
  const Eigen::Vector3d b_W = t.origin_W + Eigen::Vector3d(c.x, c.y, c.z);
  const double d_sq = (b_W - p_W).squaredNorm();
  if (d_sq <= max_sq && d_sq < best_sq) {  // strict: on a tie the lower tile key (visited first) wins
    best_sq = d_sq;
    best = TwinMatch{b_W, t.normals[i].cast<double>(), std::sqrt(d_sq)};
  }
}

std::vector<std::optional<TwinMatch>> TwinTileIndex::nearest_batch(const std::vector<Eigen::Vector3d>& p_W,
                                                                   double max_dist_m) const {
  std::vector<std::optional<TwinMatch>> out;
  out.reserve(p_W.size());
  for (const Eigen::Vector3d& p : p_W) out.push_back(nearest(p, max_dist_m));
  return out;
}

}  // namespace twinslam::registration
