#pragma once
// The twin as the registration service holds it: every tile received over the wire (MapTile, latched by the tiles
// service) kept Draco-compressed, and the ones inside some vehicle's window decoded into the TwinTileIndex — each
// tile decoded and its KD-tree built once when it enters a window, dropped when no vehicle is near it any more (the
// paper code rebuilt a KD-tree over a 700 x 700 m crop on every call). Memory is bounded by the compressed tiles
// (evicted farthest-first past max_tiles) plus the tiles of the windows, whatever the size of the city.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration {

struct WindowedTwinStats {
  std::size_t added = 0, removed = 0;  // tiles that entered / left the index in this update
  double update_ms = 0.0;              // decoding and KD-tree building included [ms]
};

class WindowedTwin {
 public:
  // window_m: side of the square window around each vehicle (the paper's 150 m); tile_size_m: the store's tiles.
  WindowedTwin(double tile_size_m, double window_m, std::size_t max_tiles = 4096);

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
  bool in_some_window(const Eigen::AlignedBox3d& bounds_W) const;
  void evict();

  double window_m_;
  std::size_t max_tiles_;
  TwinTileIndex index_;
  std::map<twin::TileKey, Stored> tiles_;
  std::map<std::string, Eigen::Vector3d> vehicles_;
};

}  // namespace twinslam::registration
