#include "twinslam/tiles/tile_cache.hpp"

#include <algorithm>

namespace twinslam::tiles {

TileCache::TileCache(std::size_t capacity, Loader loader)
    : capacity_(std::max<std::size_t>(capacity, 1)), loader_(std::move(loader)) {}

std::shared_ptr<const EncodedTile> TileCache::get(const TileRecord& info) {
  const twin::TileKey& key = info.key;
  if (const auto it = by_key_.find(key); it != by_key_.end()) {
    ++hits_;
    entries_.splice(entries_.begin(), entries_, it->second);
    return it->second->tile;
  }
  ++misses_;
  auto tile = std::make_shared<const EncodedTile>(loader_(info));
  entries_.push_front({key, tile});
  by_key_[key] = entries_.begin();
  bytes_ += tile->bytes();
  while (entries_.size() > capacity_) {
    // A shared_ptr handed out earlier keeps its bytes alive until the caller drops it; the cache forgets them now.
    bytes_ -= entries_.back().tile->bytes();
    by_key_.erase(entries_.back().key);
    entries_.pop_back();
  }
  return tile;
}

}  // namespace twinslam::tiles
