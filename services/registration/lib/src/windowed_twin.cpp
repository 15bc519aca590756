#include "twinslam/registration/windowed_twin.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "twinslam/core/error.hpp"

namespace twinslam::registration {
namespace {

// Horizontal distance from p to a box (0 inside).
double horizontal_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p) {
  const double dx = std::max({box.min().x() - p.x(), 0.0, p.x() - box.max().x()});
  const double dy = std::max({box.min().y() - p.y(), 0.0, p.y() - box.max().y()});
  return std::hypot(dx, dy);
}

// Chebyshev (square window) distance from p to a box, horizontally.
double square_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p) {
  const double dx = std::max({box.min().x() - p.x(), 0.0, p.x() - box.max().x()});
  const double dy = std::max({box.min().y() - p.y(), 0.0, p.y() - box.max().y()});
  return std::max(dx, dy);
}

}  // namespace

WindowedTwin::WindowedTwin(double tile_size_m, double window_m, std::size_t max_tiles, double prefetch_m,
                           std::size_t prefetch_per_update, double keep_m)
    : window_m_(window_m),
      prefetch_m_(prefetch_m),
      keep_m_(keep_m),
      prefetch_per_update_(prefetch_per_update),
      max_tiles_(max_tiles),
      index_(tile_size_m) {
  if (!(window_m > 0.0) || max_tiles == 0) throw InputError("windowed twin: window_m and max_tiles must be > 0");
  if (!(prefetch_m >= 0.0) || !(keep_m >= 0.0)) throw InputError("windowed twin: prefetch_m and keep_m must be >= 0");
}

double WindowedTwin::window_distance(const Eigen::AlignedBox3d& bounds_W) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& [id, p] : vehicles_) d = std::min(d, square_distance(bounds_W, p));
  return d;
}

void WindowedTwin::add_tile(const twin::TileKey& key, const Eigen::AlignedBox3d& bounds_W,
                            std::vector<std::uint8_t> points_draco) {
  tiles_[key] = {bounds_W, std::move(points_draco)};
  if (index_.contains(key)) index_.remove_tile(key);  // the next update indexes the new content
  evict();
}

void WindowedTwin::evict() {
  while (tiles_.size() > max_tiles_) {
    // Drop the stored tile farthest from every vehicle (never one in a window while others are not).
    auto worst = tiles_.end();
    double worst_d = -1.0;
    for (auto it = tiles_.begin(); it != tiles_.end(); ++it) {
      double d = std::numeric_limits<double>::infinity();
      for (const auto& [id, p] : vehicles_) d = std::min(d, horizontal_distance(it->second.bounds_W, p));
      if (worst == tiles_.end() || d > worst_d) worst_d = d, worst = it;  // NaN bounds: still evictable
    }
    index_.remove_tile(worst->first);
    tiles_.erase(worst);
  }
}

WindowedTwinStats WindowedTwin::update(const std::string& vehicle, const Eigen::Vector3d& p_W) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!p_W.allFinite() || p_W.cwiseAbs().maxCoeff() > kMaxWorldCoordinate_m) {
    throw InputError("vehicle position not finite or beyond the world's extent (1e7 m from W's origin)");
  }
  vehicles_[vehicle] = p_W;
  WindowedTwinStats stats;
  std::string failed;
  const auto build = [&](const twin::TileKey& key) {
    try {
      add_tile_from_draco(index_, key, tiles_.at(key).points_draco);
      ++stats.added;
      return true;
    } catch (const InputError& e) {
      failed = e.what();
      tiles_.erase(key);
      return false;
    }
  };
  const double half = 0.5 * window_m_;
  std::vector<std::pair<double, twin::TileKey>> ring;  // (distance, key) of ring tiles not indexed yet
  std::vector<twin::TileKey> needed;
  for (const auto& [key, tile] : tiles_) {
    const double d = window_distance(tile.bounds_W);
    const bool have = index_.contains(key);
    if (d <= half && !have) {
      needed.push_back(key);
    } else if (d <= half + prefetch_m_ && !have) {
      ring.emplace_back(d, key);
    } else if (d > half + prefetch_m_ + keep_m_ && have) {
      index_.remove_tile(key);
      ++stats.removed;
    }
  }
  for (const auto& key : needed) build(key);
  std::sort(ring.begin(), ring.end());  // nearest first, then by key: deterministic
  for (std::size_t i = 0; i < ring.size() && stats.prefetched < prefetch_per_update_; ++i) {
    if (build(ring[i].second)) ++stats.prefetched;
  }
  stats.update_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!failed.empty()) throw InputError(failed);
  return stats;
}

bool WindowedTwin::covers(const Eigen::Vector3d& p_W, double radius_m) const {
  for (const auto& key : index_.keys()) {
    const auto it = tiles_.find(key);
    if (it != tiles_.end() && horizontal_distance(it->second.bounds_W, p_W) <= radius_m) return true;
  }
  return false;
}

std::size_t WindowedTwin::stored_bytes() const {
  std::size_t n = 0;
  for (const auto& [k, t] : tiles_) n += t.points_draco.size();
  return n;
}

}  // namespace twinslam::registration
