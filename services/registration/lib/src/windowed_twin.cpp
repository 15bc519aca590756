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

WindowedTwin::WindowedTwin(double tile_size_m, double window_m, std::size_t max_tiles)
    : window_m_(window_m), max_tiles_(max_tiles), index_(tile_size_m) {
  if (!(window_m > 0.0) || max_tiles == 0) throw InputError("windowed twin: window_m and max_tiles must be > 0");
}

bool WindowedTwin::in_some_window(const Eigen::AlignedBox3d& bounds_W) const {
  return std::any_of(vehicles_.begin(), vehicles_.end(),
                     [&](const auto& v) { return square_distance(bounds_W, v.second) <= 0.5 * window_m_; });
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
      if (d > worst_d) worst_d = d, worst = it;
    }
    index_.remove_tile(worst->first);
    tiles_.erase(worst);
  }
}

WindowedTwinStats WindowedTwin::update(const std::string& vehicle, const Eigen::Vector3d& p_W) {
  const auto t0 = std::chrono::steady_clock::now();
  vehicles_[vehicle] = p_W;
  WindowedTwinStats stats;
  std::string failed;
  for (auto it = tiles_.begin(); it != tiles_.end();) {
    const bool want = in_some_window(it->second.bounds_W);
    const bool have = index_.contains(it->first);
    if (want && !have) {
      try {
        add_tile_from_draco(index_, it->first, it->second.points_draco);
        ++stats.added;
      } catch (const InputError& e) {
        failed = e.what();
        it = tiles_.erase(it);
        continue;
      }
    } else if (!want && have) {
      index_.remove_tile(it->first);
      ++stats.removed;
    }
    ++it;
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
