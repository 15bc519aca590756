#include "twinslam/tiles/tile_streamer.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"

namespace twinslam::tiles {

TileStreamer::TileStreamer(const twin::TwinIndex& index, double window_m, std::size_t max_on_wire)
    : grid_(index), half_size_m_(0.5 * window_m), max_on_wire_(max_on_wire) {}

bool TileStreamer::admit(KeySet& held, const twin::TileKey& key, bool* newly_published) {
  *newly_published = false;
  if (published_.count(key) == 0) {
    if (published_.size() >= max_on_wire_) return false;
    published_.insert(key);
    first_writes_.insert(key);
    *newly_published = true;
  }
  held.insert(key);
  return true;
}

void TileStreamer::sort_nearest(std::vector<twin::TileKey>* keys, const Eigen::Vector2d& p_W) const {
  // Nearest first: if the link is slow, the tile under the vehicle arrives before the window's corners.
  std::stable_sort(keys->begin(), keys->end(), [&](const twin::TileKey& a, const twin::TileKey& b) {
    return grid_.distance_to_square(a, p_W) < grid_.distance_to_square(b, p_W);
  });
}

void TileStreamer::admit_window(KeySet& held, const Window& window, StreamDecision& d) {
  for (const twin::TileKey& key : grid_.tiles_in(window)) {
    if (held.count(key) != 0) continue;
    bool newly_published = false;
    if (!admit(held, key, &newly_published)) {
      d.over_limit.push_back(key);
      continue;
    }
    d.new_for_vehicle.push_back(key);
    if (newly_published) d.publish.push_back(key);
  }
  sort_nearest(&d.new_for_vehicle, window.center_W);
  sort_nearest(&d.publish, window.center_W);
}

StreamDecision TileStreamer::update(const std::string& vehicle, const Eigen::Vector3d& p_W) {
  StreamDecision d;
  first_writes_.clear();
  if (!p_W.allFinite()) return d;
  const Eigen::Vector2d p = p_W.head<2>();
  admit_window(held_[vehicle], {p, half_size_m_}, d);
  return d;
}

StreamDecision TileStreamer::request(const std::string& vehicle, const Eigen::Vector2d& center_W, double half_size_m,
                                     const std::vector<twin::TileKey>& have) {
  if (!center_W.allFinite()) throw InputError("tile request of '" + vehicle + "': window centre is not finite");
  if (!std::isfinite(half_size_m) || half_size_m <= 0.0) {
    throw InputError("tile request of '" + vehicle + "': half_size_m must be finite and > 0, got " +
                     std::to_string(half_size_m));
  }
  KeySet& held = held_[vehicle];
  held = KeySet(have.begin(), have.end());
  StreamDecision d;
  first_writes_.clear();
  admit_window(held, {center_W, half_size_m}, d);
  d.publish = d.new_for_vehicle;  // the requester says it lacks them: latched or not, send them again
  return d;
}

void TileStreamer::publish_failed(const twin::TileKey& key) {
  // Only a failed first write leaves the tile off the wire. A failed re-send (a request) leaves the writer's latched
  // sample of that instance, which still counts against max_on_wire: forgetting it let a fuzzed run of requests with
  // failing writes latch more tiles than the writer can hold.
  if (first_writes_.erase(key) != 0) published_.erase(key);
  for (auto& [vehicle, held] : held_) held.erase(key);
}

bool TileStreamer::holds(const std::string& vehicle, const twin::TileKey& key) const {
  const auto it = held_.find(vehicle);
  return it != held_.end() && it->second.count(key) != 0;
}

std::size_t TileStreamer::memory_bytes() const {
  // A set node is roughly key + next pointer + cached hash; buckets are one pointer each.
  const std::size_t node = sizeof(twin::TileKey) + 2 * sizeof(void*);
  std::size_t bytes = sizeof(*this) + grid_.memory_bytes() - sizeof(grid_) + published_.size() * node +
                      published_.bucket_count() * sizeof(void*);
  for (const auto& [vehicle, held] : held_) {
    bytes += vehicle.capacity() + sizeof(held) + held.size() * node + held.bucket_count() * sizeof(void*);
  }
  return bytes;
}

}  // namespace twinslam::tiles
