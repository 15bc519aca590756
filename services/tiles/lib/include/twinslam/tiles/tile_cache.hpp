#pragma once
// LRU of encoded tiles (the Draco bytes MapTile carries), so a tile sent again (a TileRequest) needs no disk read and
// memory stays bounded by `capacity` tiles whatever the size of the city.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "twinslam/tiles/tile_grid.hpp"

namespace twinslam::tiles {

struct EncodedTile {
  std::vector<std::uint8_t> mesh_draco;
  std::vector<std::uint8_t> points_draco;
  std::size_t bytes() const { return mesh_draco.size() + points_draco.size(); }
};

class TileCache {
 public:
  using Loader = std::function<EncodedTile(const TileRecord&)>;
  // Reads a tile's Draco files from a twin store (twin::read_tile_file; throws InputError if missing). The store
  // writes no mesh file for a tile without triangles and no points file for one without points: those stay empty.
  static Loader store_loader(const std::string& twin_dir);

  // capacity >= 1 tiles (TilesConfig::cache_tiles, validated there).
  TileCache(std::size_t capacity, Loader loader);

  // The tile's bytes, loaded on a miss (the loader's InputError passes through and nothing is cached).
  std::shared_ptr<const EncodedTile> get(const TileRecord& info);

  std::size_t size() const { return entries_.size(); }
  std::size_t bytes() const { return bytes_; }  // encoded bytes held
  unsigned long long hits() const { return hits_; }
  unsigned long long misses() const { return misses_; }

 private:
  struct Entry {
    twin::TileKey key;
    std::shared_ptr<const EncodedTile> tile;
  };
  std::size_t capacity_;
  Loader loader_;
  std::list<Entry> entries_;  // most recently used first
  std::unordered_map<twin::TileKey, std::list<Entry>::iterator, TileKeyHash> by_key_;
  std::size_t bytes_ = 0;
  unsigned long long hits_ = 0, misses_ = 0;
};

}  // namespace twinslam::tiles
