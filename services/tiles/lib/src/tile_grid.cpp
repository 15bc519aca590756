#include "twinslam/tiles/tile_grid.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "twinslam/core/error.hpp"

namespace twinslam::tiles {

TileGrid::TileGrid(twin::TwinIndex index) : index_(std::move(index)) {
  if (!std::isfinite(index_.tile_size_m) || index_.tile_size_m <= 0.0) {
    throw InputError("twin index: tile size must be finite and > 0, got " + std::to_string(index_.tile_size_m));
  }
  by_key_.reserve(index_.tiles.size());
  for (std::size_t i = 0; i < index_.tiles.size(); ++i) {
    const twin::TileKey& k = index_.tiles[i].key;
    by_key_.emplace(k, i);
    if (i == 0) {
      min_ix_ = max_ix_ = k.ix;
      min_iy_ = max_iy_ = k.iy;
    }
    min_ix_ = std::min(min_ix_, k.ix);
    max_ix_ = std::max(max_ix_, k.ix);
    min_iy_ = std::min(min_iy_, k.iy);
    max_iy_ = std::max(max_iy_, k.iy);
  }
}

const twin::TileInfo* TileGrid::find(const twin::TileKey& key) const {
  const auto it = by_key_.find(key);
  return it == by_key_.end() ? nullptr : &index_.tiles[it->second];
}

std::vector<twin::TileKey> TileGrid::tiles_in(const Window& window) const {
  std::vector<twin::TileKey> keys;
  const double s = index_.tile_size_m;
  const double h = window.half_size_m;
  if (!window.center_W.allFinite() || !std::isfinite(h) || h < 0.0 || index_.tiles.empty()) return keys;
  // Half-open like the store's tiles: tile [ix s, (ix+1) s) meets the window [e - h, e + h) iff
  // floor((e - h) / s) <= ix <= ceil((e + h) / s) - 1, so a tile that only touches the window's edge is not sent.
  // Clamped to the stored key range in double first, so a far-away or huge window cannot overflow int.
  auto range = [&](double c, int lo, int hi, int* first, int* last) {
    const double a = std::max(std::floor((c - h) / s), static_cast<double>(lo));
    const double b = std::min(std::ceil((c + h) / s) - 1.0, static_cast<double>(hi));
    *first = static_cast<int>(a);
    *last = a <= b ? static_cast<int>(b) : *first - 1;
  };
  int ix0, ix1, iy0, iy1;
  range(window.center_W.x(), min_ix_, max_ix_, &ix0, &ix1);
  range(window.center_W.y(), min_iy_, max_iy_, &iy0, &iy1);
  for (int ix = ix0; ix <= ix1; ++ix) {
    for (int iy = iy0; iy <= iy1; ++iy) {
      if (by_key_.count({ix, iy}) != 0) keys.push_back({ix, iy});
    }
  }
  return keys;  // ix-major, iy-minor: the order of TileKey's <=>
}

double TileGrid::distance_to_square(const twin::TileKey& key, const Eigen::Vector2d& p_W) const {
  const double s = index_.tile_size_m;
  const Eigen::Vector2d lo(key.ix * s, key.iy * s);
  const Eigen::Vector2d hi = lo + Eigen::Vector2d(s, s);
  const Eigen::Vector2d d = (lo - p_W).cwiseMax(p_W - hi).cwiseMax(Eigen::Vector2d::Zero());
  return d.norm();
}

// Same text as TileKey::str() ("<ix>_<iy>", the store's file names); spelled here so this pure lookup needs no store code.
std::string TileGrid::wire_key(const twin::TileKey& key) const {
  return index_.twin_id + "/" + std::to_string(key.ix) + "_" + std::to_string(key.iy);
}

std::optional<twin::TileKey> TileGrid::parse_wire_key(std::string_view text) const {
  const auto slash = text.rfind('/');
  if (slash != std::string_view::npos) {
    if (text.substr(0, slash) != index_.twin_id) return std::nullopt;
    text = text.substr(slash + 1);
  }
  const auto sep = text.find('_', 1);  // from 1: a leading '-' is the sign of ix
  if (sep == std::string_view::npos) return std::nullopt;
  twin::TileKey key;
  const char* end_x = text.data() + sep;
  const char* end_y = text.data() + text.size();
  const auto rx = std::from_chars(text.data(), end_x, key.ix);
  const auto ry = std::from_chars(end_x + 1, end_y, key.iy);
  if (rx.ec != std::errc() || rx.ptr != end_x || ry.ec != std::errc() || ry.ptr != end_y) return std::nullopt;
  return key;
}

std::size_t TileGrid::memory_bytes() const {
  return sizeof(*this) + index_.tiles.capacity() * sizeof(twin::TileInfo) + index_.twin_id.capacity() +
         by_key_.bucket_count() * sizeof(void*) +
         by_key_.size() * (sizeof(std::pair<const twin::TileKey, std::size_t>) + 2 * sizeof(void*));
}

}  // namespace twinslam::tiles
