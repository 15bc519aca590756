#pragma once
// O(window) lookup of the twin's tiles, in memory that stays small however large the city: per stored tile one
// 40-byte record (key, content bounds as floats relative to the tile's corner, counts) and, when the tiles fill their
// key range densely (a city), a 4-byte cell table indexed by (ix, iy) — so the tiles around a vehicle are found by
// visiting only the cells its window covers (at most (window / tile + 1)^2), never by scanning the city. A sparse
// twin (tiles far apart) falls back to a binary search per window column instead of a huge cell table.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/twin/store.hpp"

namespace twinslam::tiles {

struct TileKeyHash {
  std::size_t operator()(const twin::TileKey& k) const {
    return std::hash<std::uint64_t>()((static_cast<std::uint64_t>(static_cast<std::uint32_t>(k.ix)) << 32) |
                                      static_cast<std::uint32_t>(k.iy));
  }
};

// A horizontal square window: centre (e, n) in W and half its side [m].
struct Window {
  Eigen::Vector2d center_W = Eigen::Vector2d::Zero();
  double half_size_m = 75.0;
};

// What the service keeps of a stored tile (twin::TileInfo minus what it never needs).
struct TileRecord {
  twin::TileKey key;
  float lo_T[3] = {0, 0, 0};  // content bounds relative to the tile's corner (ix s, iy s, 0) [m]: float is
  float hi_T[3] = {0, 0, 0};  // then exact to ~10 um whatever the distance from the origin
  std::uint32_t triangles = 0;
  std::uint32_t points = 0;
};

class TileGrid {
 public:
  // Throws InputError when the index's tile size is not finite and positive or a tile's counts exceed 32 bits.
  explicit TileGrid(const twin::TwinIndex& index);

  const twin::GeoOrigin& origin() const { return origin_; }
  const std::string& twin_id() const { return twin_id_; }
  double tile_size_m() const { return tile_size_m_; }
  const std::vector<TileRecord>& records() const { return records_; }  // sorted by key
  const TileRecord* find(const twin::TileKey& key) const;               // nullptr if not stored
  Eigen::AlignedBox3d bounds_W(const TileRecord& r) const;              // content bounds [m, W]

  // Keys of the stored tiles whose grid square [ix s, (ix+1) s) x [iy s, (iy+1) s) meets the window
  // [e - h, e + h) x [n - h, n + h), in key order. Only cells inside the stored key range are visited, so even a huge
  // window costs at most the grid's size.
  std::vector<twin::TileKey> tiles_in(const Window& window) const;

  // Horizontal distance from p (E, N) to the tile's grid square [m] (0 inside).
  double distance_to_square(const twin::TileKey& key, const Eigen::Vector2d& p_W) const;

  // "<twin id>/<ix>_<iy>" as on the wire (MapTile.tile_key), and its inverse (also accepts a bare "<ix>_<iy>");
  // nullopt for a key of another twin or a malformed one.
  std::string wire_key(const twin::TileKey& key) const;
  std::optional<twin::TileKey> parse_wire_key(std::string_view text) const;

  // Memory held by the records and the cell table [bytes].
  std::size_t memory_bytes() const;

 private:
  std::int32_t position(const twin::TileKey& key) const;  // in records_, -1 if absent

  twin::GeoOrigin origin_;
  std::string twin_id_;
  double tile_size_m_ = 50.0;
  std::vector<TileRecord> records_;
  std::vector<std::int32_t> cells_;  // dense case: (iy - min_iy) * width + (ix - min_ix) -> records_ position or -1
  int min_ix_ = 0, max_ix_ = -1, min_iy_ = 0, max_iy_ = -1;  // key range of the stored tiles
};

}  // namespace twinslam::tiles
