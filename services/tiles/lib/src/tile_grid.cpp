#include "twinslam/tiles/tile_grid.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "twinslam/core/error.hpp"

namespace twinslam::tiles {

TileGrid::TileGrid(const twin::TwinIndex& index)
    : origin_(index.origin), twin_id_(index.twin_id), tile_size_m_(index.tile_size_m) {
  if (!std::isfinite(tile_size_m_) || tile_size_m_ <= 0.0) {
    throw InputError("twin index: tile size must be finite and > 0, got " + std::to_string(tile_size_m_));
  }
  records_.reserve(index.tiles.size());
  for (const twin::TileInfo& info : index.tiles) {
    if (info.triangles > UINT32_MAX || info.points > UINT32_MAX) {
      throw InputError("twin index: tile " + info.key.str() + " has more than 2^32 triangles or points");
    }
    TileRecord r;
    r.key = info.key;
    r.triangles = static_cast<std::uint32_t>(info.triangles);
    r.points = static_cast<std::uint32_t>(info.points);
    if (!info.bounds_W.isEmpty()) {
      const Eigen::Vector3d corner(info.key.ix * tile_size_m_, info.key.iy * tile_size_m_, 0.0);
      const Eigen::Vector3f lo = (info.bounds_W.min() - corner).cast<float>();
      const Eigen::Vector3f hi = (info.bounds_W.max() - corner).cast<float>();
      std::copy(lo.data(), lo.data() + 3, r.lo_T);
      std::copy(hi.data(), hi.data() + 3, r.hi_T);
    }
    records_.push_back(r);
  }
  std::sort(records_.begin(), records_.end(), [](const TileRecord& a, const TileRecord& b) { return a.key < b.key; });
  if (records_.empty()) return;
  min_ix_ = records_.front().key.ix;
  max_ix_ = records_.back().key.ix;
  min_iy_ = max_iy_ = records_.front().key.iy;
  for (const TileRecord& r : records_) {
    min_iy_ = std::min(min_iy_, r.key.iy);
    max_iy_ = std::max(max_iy_, r.key.iy);
  }
  // Dense enough (a city fills its key range): a cell table, 4 bytes per cell, at most ~4x the records' count.
  const double cells = (static_cast<double>(max_ix_) - min_ix_ + 1) * (static_cast<double>(max_iy_) - min_iy_ + 1);
  if (cells <= 4.0 * static_cast<double>(records_.size()) + 4096.0) {
    cells_.assign(static_cast<std::size_t>(cells), -1);
    const std::size_t width = static_cast<std::size_t>(max_ix_ - min_ix_ + 1);
    for (std::size_t i = 0; i < records_.size(); ++i) {
      const twin::TileKey& k = records_[i].key;
      cells_[static_cast<std::size_t>(k.iy - min_iy_) * width + static_cast<std::size_t>(k.ix - min_ix_)] =
          static_cast<std::int32_t>(i);
    }
  }
}

std::int32_t TileGrid::position(const twin::TileKey& key) const {
  if (key.ix < min_ix_ || key.ix > max_ix_ || key.iy < min_iy_ || key.iy > max_iy_) return -1;
  if (!cells_.empty()) {
    const std::size_t width = static_cast<std::size_t>(max_ix_ - min_ix_ + 1);
    return cells_[static_cast<std::size_t>(key.iy - min_iy_) * width + static_cast<std::size_t>(key.ix - min_ix_)];
  }
  const auto it = std::lower_bound(records_.begin(), records_.end(), key,
                                   [](const TileRecord& r, const twin::TileKey& k) { return r.key < k; });
  return it != records_.end() && it->key == key ? static_cast<std::int32_t>(it - records_.begin()) : -1;
}

const TileRecord* TileGrid::find(const twin::TileKey& key) const {
  const std::int32_t i = position(key);
  return i < 0 ? nullptr : &records_[static_cast<std::size_t>(i)];
}

Eigen::AlignedBox3d TileGrid::bounds_W(const TileRecord& r) const {
  const Eigen::Vector3d corner(r.key.ix * tile_size_m_, r.key.iy * tile_size_m_, 0.0);
  return {corner + Eigen::Vector3f(r.lo_T[0], r.lo_T[1], r.lo_T[2]).cast<double>(),
          corner + Eigen::Vector3f(r.hi_T[0], r.hi_T[1], r.hi_T[2]).cast<double>()};
}

std::vector<twin::TileKey> TileGrid::tiles_in(const Window& window) const {
  std::vector<twin::TileKey> keys;
  const double s = tile_size_m_;
  const double h = window.half_size_m;
  if (!window.center_W.allFinite() || !std::isfinite(h) || h < 0.0 || records_.empty()) return keys;
  // Half-open like the store's tiles: tile [ix s, (ix+1) s) meets the window [e - h, e + h) iff
  // floor((e - h) / s) <= ix <= ceil((e + h) / s) - 1, so a tile that only touches the window's edge is not sent.
  // Clamped to the stored key range in double first, so a far-away or huge window cannot overflow int.
  auto range = [&](double c, int lo, int hi, int* first, int* last) {
    const double a = std::max(std::floor((c - h) / s), static_cast<double>(lo));
    const double b = std::min(std::ceil((c + h) / s) - 1.0, static_cast<double>(hi));
    if (!(a <= b)) {  // beyond the stored range (or NaN from inf - inf): a or b may not fit an int
      *first = 0;
      *last = -1;
      return;
    }
    *first = static_cast<int>(a);
    *last = static_cast<int>(b);
  };
  int ix0, ix1, iy0, iy1;
  range(window.center_W.x(), min_ix_, max_ix_, &ix0, &ix1);
  range(window.center_W.y(), min_iy_, max_iy_, &iy0, &iy1);
  for (int ix = ix0; ix <= ix1; ++ix) {
    if (!cells_.empty()) {
      for (int iy = iy0; iy <= iy1; ++iy) {
        if (position({ix, iy}) >= 0) keys.push_back({ix, iy});
      }
      continue;
    }
    // Sparse: the column's stored tiles are contiguous in key order.
    auto it = std::lower_bound(records_.begin(), records_.end(), twin::TileKey{ix, iy0},
                               [](const TileRecord& r, const twin::TileKey& k) { return r.key < k; });
    for (; it != records_.end() && it->key.ix == ix && it->key.iy <= iy1; ++it) keys.push_back(it->key);
  }
  return keys;  // ix-major, iy-minor: the order of TileKey's <=>
}

double TileGrid::distance_to_square(const twin::TileKey& key, const Eigen::Vector2d& p_W) const {
  const double s = tile_size_m_;
  const Eigen::Vector2d lo(key.ix * s, key.iy * s);
  const Eigen::Vector2d hi = lo + Eigen::Vector2d(s, s);
  const Eigen::Vector2d d = (lo - p_W).cwiseMax(p_W - hi).cwiseMax(Eigen::Vector2d::Zero());
  return d.norm();
}

std::string TileGrid::wire_key(const twin::TileKey& key) const { return twin_id_ + "/" + key.str(); }

std::optional<twin::TileKey> TileGrid::parse_wire_key(std::string_view text) const {
  const auto slash = text.rfind('/');
  if (slash != std::string_view::npos) {
    if (text.substr(0, slash) != twin_id_) return std::nullopt;
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
  return sizeof(*this) + twin_id_.capacity() + records_.capacity() * sizeof(TileRecord) +
         cells_.capacity() * sizeof(std::int32_t);
}

}  // namespace twinslam::tiles
