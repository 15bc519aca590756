#pragma once
// The twin as the registration service holds it: every tile received over the wire (MapTile, latched by the tiles
// service) kept Draco-compressed, and the ones inside some vehicle's window decoded into the TwinTileIndex — each
// tile decoded and its KD-tree built once when it enters a window, dropped when no vehicle is near it any more (the
// paper code rebuilt a KD-tree over a 700 x 700 m crop on every call). Memory is bounded by the compressed tiles
// (evicted farthest-first past max_tiles) plus the tiles of the windows, whatever the size of the city.
// Prefetch: tiles within a ring of `prefetch_m` around a window are indexed too, at most `prefetch_per_update` per
// update (nearest first), so that crossing a tile border costs no more than that many tile builds (the tiles entering
// the window were built on earlier keyframes) instead of a whole row at once: that row was the p99 of a keyframe's
// registration time in bench_registration. A tile inside a window that is not indexed yet is always built at once.
// Hysteresis: an indexed tile is dropped only beyond the ring plus `keep_m`, so a vehicle circling near a ring border
// does not decode and build the same tiles again and again (on city-loops' flight it did: a quarter of the keyframes
// paid two tile builds of ~4.5 ms each, decoding included).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration {

struct WindowedTwinStats {
  std::size_t added = 0, removed = 0;  // tiles that entered / left the index in this update (prefetched included)
  std::size_t prefetched = 0;          // of `added`: tiles of the prefetch ring
  double update_ms = 0.0;              // decoding and KD-tree building included [ms]
};

class WindowedTwin {
 public:
  // window_m: side of the square window around each vehicle (the paper's 150 m); tile_size_m: the store's tiles.
  // prefetch_m: width of the ring around the window whose tiles are indexed ahead [m] (0: none);
  // prefetch_per_update: ring tiles built per update at most; keep_m: indexed tiles are dropped beyond the ring
  // plus this [m].
  WindowedTwin(double tile_size_m, double window_m, std::size_t max_tiles = 4096, double prefetch_m = 50.0,
               std::size_t prefetch_per_update = 1, double keep_m = 50.0);

  // A tile from the wire (replaces one of the same key; re-indexed if it was indexed). bounds_W: of its content.
  void add_tile(const twin::TileKey& key, const Eigen::AlignedBox3d& bounds_W, std::vector<std::uint8_t> points_draco);
  // Moves `vehicle` to p_W and brings the index up to date. InputError if a tile entering the window does not decode
  // (the tile is dropped and named; the others stay).
  WindowedTwinStats update(const std::string& vehicle, const Eigen::Vector3d& p_W);

  const TwinTileIndex& index() const { return index_; }
  // Whether some indexed tile's content lies within `radius_m` (horizontally) of p_W.
  bool covers(const Eigen::Vector3d& p_W, double radius_m) const;
  std::size_t stored_tiles() const { return tiles_.size(); }
  std::size_t stored_bytes() const;

 private:
  struct Stored {
    Eigen::AlignedBox3d bounds_W;
    std::vector<std::uint8_t> points_draco;
  };
  double window_distance(const Eigen::AlignedBox3d& bounds_W) const;  // nearest vehicle, square metric [m]
  void evict();

  double window_m_;
  double prefetch_m_;
  double keep_m_;
  std::size_t prefetch_per_update_;
  std::size_t max_tiles_;
  TwinTileIndex index_;
  std::map<twin::TileKey, Stored> tiles_;
  std::map<std::string, Eigen::Vector3d> vehicles_;
};

}  // namespace twinslam::registration
