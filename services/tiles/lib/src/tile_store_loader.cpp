// The store-backed loader of TileCache, in its own file: the cache itself needs no store code (tests give it theirs).
#include "twinslam/tiles/tile_cache.hpp"

namespace twinslam::tiles {

TileCache::Loader TileCache::store_loader(const std::string& twin_dir) {
  return [twin_dir](const TileRecord& info) {
    EncodedTile t;
    if (info.triangles > 0) t.mesh_draco = twin::read_tile_file(twin_dir, info.key, false);
    if (info.points > 0) t.points_draco = twin::read_tile_file(twin_dir, info.key, true);
    return t;
  };
}

}  // namespace twinslam::tiles
