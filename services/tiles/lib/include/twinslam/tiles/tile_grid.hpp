#pragma once
// O(window) lookup of the twin's tiles: a hash map from tile key to the index's TileInfo, so the tiles around a
// vehicle are found by visiting only the grid cells its window covers (at most (window / tile + 2)^2 cells), never by
// scanning every tile of the city. The cost of a lookup does not grow with the city.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

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

class TileGrid {
 public:
  // Throws InputError when the index's tile size is not finite and positive.
  explicit TileGrid(twin::TwinIndex index);

  const twin::TwinIndex& index() const { return index_; }
  double tile_size_m() const { return index_.tile_size_m; }
  const twin::TileInfo* find(const twin::TileKey& key) const;

  // Keys of the stored tiles whose grid square [ix s, (ix+1) s) x [iy s, (iy+1) s) meets the window
  // [e - h, e + h) x [n - h, n + h), in key order. Cells outside the
  // index's key range are not visited, so even a huge window costs at most the grid's size.
  std::vector<twin::TileKey> tiles_in(const Window& window) const;

  // Horizontal distance from p (E, N) to the tile's grid square [m] (0 inside).
  double distance_to_square(const twin::TileKey& key, const Eigen::Vector2d& p_W) const;

  // "<twin id>/<ix>_<iy>" as on the wire (MapTile.tile_key), and its inverse (also accepts a bare "<ix>_<iy>");
  // nullopt for a key of another twin or a malformed one.
  std::string wire_key(const twin::TileKey& key) const;
  std::optional<twin::TileKey> parse_wire_key(std::string_view text) const;

  // Memory held by the index and the hash map [bytes] (approximate: element sizes, not allocator overhead).
  std::size_t memory_bytes() const;

 private:
  twin::TwinIndex index_;
  std::unordered_map<twin::TileKey, std::size_t, TileKeyHash> by_key_;  // -> index_.tiles position
  int min_ix_ = 0, max_ix_ = -1, min_iy_ = 0, max_iy_ = -1;               // key range of the stored tiles
};

}  // namespace twinslam::tiles
