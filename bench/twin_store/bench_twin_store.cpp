// Twin store speed (issue 7): Draco encode / decode of one 50 m tile of the procedural city (the tiles service decodes
// on request, the map-matching side per tile in view), as mesh and as sampled points; plus the whole store build.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>

#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/twin.hpp"
#include "twinslam/twin/store.hpp"
#include "twinslam/twin/tiling.hpp"

namespace {

using namespace twinslam;

// The default scenario's twin (600 m city, details removed, 0.2 m surface noise) as a twin::Mesh.
const twin::Mesh& city_twin() {
  static const twin::Mesh mesh = [] {
    const sim::City city = sim::build_city(sim::CityConfig{}, 7);
    const sim::Twin t = sim::derive_twin(city, sim::TwinConfig{}, 7);
    twin::Mesh m;
    m.p_W = t.mesh.p_W;
    m.triangles = t.mesh.triangles;
    return m;
  }();
  return mesh;
}

// The tile with the most triangles (tower and blocks): the expensive case.
struct BusyTile {
  twin::Mesh mesh, points;
  twin::TileKey key;
};
const BusyTile& busy_tile() {
  static const BusyTile tile = [] {
    const twin::StoreConfig config;
    const auto tiles = twin::cut_into_tiles(city_twin(), config.tile_size_m);
    const auto it = std::max_element(tiles.begin(), tiles.end(), [](const auto& a, const auto& b) {
      return a.second.num_triangles() < b.second.num_triangles();
    });
    BusyTile t{it->second, twin::sample_points(it->second, config.point_spacing_m, config.seed), it->first};
    return t;
  }();
  return tile;
}

void BM_EncodeMeshTile(benchmark::State& state) {
  const BusyTile& t = busy_tile();
  const twin::StoreConfig config;
  std::size_t bytes = 0;
  for (auto _ : state) bytes = twin::encode_mesh(t.mesh, config, twin::tile_origin_W(t.key, 50.0)).size();
  state.SetItemsProcessed(state.iterations());  // items = tiles
  state.counters["triangles"] = static_cast<double>(t.mesh.num_triangles());
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_DecodeMeshTile(benchmark::State& state) {
  const BusyTile& t = busy_tile();
  const auto bytes = twin::encode_mesh(t.mesh, twin::StoreConfig{}, twin::tile_origin_W(t.key, 50.0));
  for (auto _ : state) benchmark::DoNotOptimize(twin::decode_draco(bytes.data(), bytes.size(), "tile"));
  state.SetItemsProcessed(state.iterations());
  state.counters["triangles"] = static_cast<double>(t.mesh.num_triangles());
}

void BM_EncodePointsTile(benchmark::State& state) {
  const BusyTile& t = busy_tile();
  const twin::StoreConfig config;
  std::size_t bytes = 0;
  for (auto _ : state) bytes = twin::encode_points(t.points, config, twin::tile_origin_W(t.key, 50.0)).size();
  state.SetItemsProcessed(state.iterations());
  state.counters["points"] = static_cast<double>(t.points.p_W.size());
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_DecodePointsTile(benchmark::State& state) {
  const BusyTile& t = busy_tile();
  const auto bytes = twin::encode_points(t.points, twin::StoreConfig{}, twin::tile_origin_W(t.key, 50.0));
  for (auto _ : state) benchmark::DoNotOptimize(twin::decode_draco(bytes.data(), bytes.size(), "tile"));
  state.SetItemsProcessed(state.iterations());
  state.counters["points"] = static_cast<double>(t.points.p_W.size());
}

// Cut + sample + encode + write the whole 600 m city (what `twinslam twin build` does after loading).
void BM_BuildStore(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / ("bench_twin_store_" + std::to_string(::getpid()));
  twin::TwinIndex index;
  for (auto _ : state)
    index =
        twin::build_twin_store(city_twin(), twin::GeoOrigin{47.3769, 8.5417, 408.0}, twin::StoreConfig{}, dir.string());
  std::filesystem::remove_all(dir);
  state.counters["tiles"] = static_cast<double>(index.tiles.size());
  state.counters["triangles"] = static_cast<double>(index.triangles);
  state.counters["points"] = static_cast<double>(index.points);
}

BENCHMARK(BM_EncodeMeshTile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodeMeshTile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EncodePointsTile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodePointsTile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuildStore)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
