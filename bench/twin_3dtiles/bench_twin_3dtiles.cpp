// 3D Tiles loading cost: a whole tileset into W (file reads, b3dm / glb parsing, placement through ECEF -> ENU),
// and its parts, to see where the time goes.
#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "twinslam/twin/b3dm.hpp"
#include "twinslam/twin/gltf.hpp"
#include "twinslam/twin/tiles3d.hpp"

namespace {

std::string sample(const std::string& rel) { return std::string(TWINSLAM_SHARED_DIR) + "/data/3dtiles/" + rel; }

twinslam::twin::LoadOptions city_options() {
  twinslam::twin::LoadOptions o;
  constexpr double kDeg = 180.0 / std::numbers::pi;
  o.origin = {0.698874 * kDeg, -1.31968 * kDeg, 0.0};
  return o;
}

void BM_LoadCityTileset(benchmark::State& state) {
  const std::string path = sample("cesium-samples/TilesetWithRequestVolume/city/tileset.json");
  const auto options = city_options();
  std::size_t triangles = 0;
  for (auto _ : state) {
    twinslam::twin::LoadReport report;
    const auto mesh = twinslam::twin::load_3dtiles(path, options, &report);
    triangles = mesh.num_triangles();
    benchmark::DoNotOptimize(triangles);
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_LoadCityTileset)->Unit(benchmark::kMillisecond);

void BM_LoadRootTilesetWithBuilding(benchmark::State& state) {
  // City plus building.b3dm (3.6 MB, ~66k triangles) under its tile transform.
  const std::string path = sample("cesium-samples/TilesetWithRequestVolume/tileset.json");
  const auto options = city_options();
  for (auto _ : state) {
    twinslam::twin::LoadReport report;
    benchmark::DoNotOptimize(twinslam::twin::load_3dtiles(path, options, &report).num_triangles());
  }
}
BENCHMARK(BM_LoadRootTilesetWithBuilding)->Unit(benchmark::kMillisecond);

void BM_ParseB3dmInMemory(benchmark::State& state) {
  const std::string path = sample("cesium-samples/TilesetWithRequestVolume/city/ll.b3dm");
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  for (auto _ : state) {
    benchmark::DoNotOptimize(twinslam::twin::parse_b3dm(bytes.data(), bytes.size(), path).gltf.mesh.num_vertices());
  }
}
BENCHMARK(BM_ParseB3dmInMemory)->Unit(benchmark::kMicrosecond);

void BM_DecodeDracoBox(benchmark::State& state) {
  const std::string path = sample("cesium-tools/BoxDraco.glb");
  for (auto _ : state) benchmark::DoNotOptimize(twinslam::twin::load_gltf_file(path).num_triangles());
}
BENCHMARK(BM_DecodeDracoBox)->Unit(benchmark::kMicrosecond);

}  // namespace
