// Building a twin store from a mesh and reading its tiles back (store.hpp).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "store_index.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/tiling.hpp"

namespace twinslam::twin {
namespace {

namespace fs = std::filesystem;

// FNV-1a 64: a stable content hash (same bytes, same id, on every machine), not a security measure.
struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

void write_bytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw InputError(where(path.string(), 0, "cannot write"));
}

// Tiles of an earlier build that this one does not have would otherwise linger next to the new index.
void remove_stale_tiles(const fs::path& tiles_dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(tiles_dir, ec)) {
    if (entry.path().extension() == ".drc") fs::remove(entry.path(), ec);
  }
}

std::uint64_t tile_stream(const TileKey& key) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(key.ix)) << 32) | static_cast<std::uint32_t>(key.iy);
}

}  // namespace

TwinIndex build_twin_store(const Mesh& mesh_W, const GeoOrigin& origin, const StoreConfig& config,
                           const std::string& out_dir, const TileProgress& on_tile) {
  config.validate();
  if (mesh_W.empty()) throw InputError(where(out_dir, 0, "the twin mesh is empty: nothing to store"));
  const bool point_source = mesh_W.triangles.empty();  // a point set with normals: its points are the sampling
  const std::map<TileKey, Mesh> meshes =
      point_source ? std::map<TileKey, Mesh>{} : cut_into_tiles(mesh_W, config.tile_size_m);
  const std::map<TileKey, Mesh> given_points =
      point_source ? split_points_into_tiles(mesh_W, config.tile_size_m) : std::map<TileKey, Mesh>{};

  const fs::path dir(out_dir), tiles_dir = dir / "tiles";
  std::error_code ec;
  fs::create_directories(tiles_dir, ec);
  if (ec) throw InputError(where(out_dir, 0, "cannot create the twin folder: " + ec.message()));
  remove_stale_tiles(tiles_dir);

  TwinIndex index;
  index.origin = origin;
  index.tile_size_m = config.tile_size_m;
  index.point_spacing_m = config.point_spacing_m;
  index.extent_W = mesh_W.bounds();
  Fnv1a id;
  for (const double v : {origin.lat_deg, origin.lon_deg, origin.alt_m})
    id.add(&v, sizeof v);  // another origin: another twin
  id.add(&config.tile_size_m, sizeof config.tile_size_m);
  std::set<TileKey> keys;
  for (const auto& [key, m] : meshes) keys.insert(key);
  for (const auto& [key, p] : given_points) keys.insert(key);
  if (on_tile) on_tile(0, keys.size());
  for (const TileKey& key : keys) {  // std::set: sorted, so the index and the id are in key order
    const auto mesh_it = meshes.find(key);
    const Mesh points = point_source
                            ? given_points.at(key)
                            : sample_points(mesh_it->second, config.point_spacing_m, config.seed, tile_stream(key));
    TileInfo info;
    info.key = key;
    info.origin_W = tile_origin_W(key, config.tile_size_m);
    if (mesh_it != meshes.end()) {
      info.triangles = mesh_it->second.num_triangles();
      info.bounds_W.extend(mesh_it->second.bounds());
      const std::vector<std::uint8_t> bytes = encode_mesh(mesh_it->second, config, info.origin_W);
      write_bytes(dir / tile_file_name(key, false), bytes);
      info.mesh_bytes = bytes.size();
      id.add(bytes.data(), bytes.size());
    }
    if (!points.empty()) {
      info.points = points.p_W.size();
      info.bounds_W.extend(points.bounds());
      const std::vector<std::uint8_t> bytes = encode_points(points, config, info.origin_W);
      write_bytes(dir / tile_file_name(key, true), bytes);
      info.points_bytes = bytes.size();
      id.add(bytes.data(), bytes.size());
    }
    info.bytes = info.mesh_bytes + info.points_bytes;
    index.triangles += info.triangles;
    index.points += info.points;
    index.tiles.push_back(info);
    if (on_tile) on_tile(index.tiles.size(), keys.size());
  }
  index.twin_id = id.hex();
  write_twin_index(index, out_dir);
  return index;
}

std::vector<std::uint8_t> read_tile_file(const std::string& twin_dir, const TileKey& key, bool points) {
  const fs::path path = fs::path(twin_dir) / tile_file_name(key, points);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where(path.string(), 0, "missing tile file"));
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(where(path.string(), 0, "cannot read"));
  return bytes;
}

Tile load_tile(const std::string& twin_dir, const TwinIndex& index, const TileKey& key) {
  const TileInfo* info = index.find(key);
  const std::string index_file = (fs::path(twin_dir) / "index.json").string();
  if (info == nullptr) throw InputError(where(index_file, 0, "has no tile " + key.str()));
  Tile tile;
  tile.info = *info;
  for (const bool points : {false, true}) {
    const std::size_t expected = points ? info->points : info->triangles;
    if (expected == 0) continue;
    const std::string file = (fs::path(twin_dir) / tile_file_name(key, points)).string();
    const std::vector<std::uint8_t> bytes = read_tile_file(twin_dir, key, points);
    Mesh m = decode_draco(bytes.data(), bytes.size(), file);
    const std::size_t got = points ? m.p_W.size() : m.triangles.size();
    if (got != expected || (points && m.n_W.size() != m.p_W.size())) {
      throw InputError(where(file, 0,
                             "holds " + std::to_string(got) + (points ? " points" : " triangles") +
                                 ", index.json says " + std::to_string(expected)));
    }
    (points ? tile.points_W : tile.mesh_W) = std::move(m);
  }
  return tile;
}

}  // namespace twinslam::twin
