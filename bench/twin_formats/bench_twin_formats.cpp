// What a `twinslam twin build` spends per source format, on the shared Delft model and generated inputs.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "twinslam/twin/cityjson.hpp"
#include "twinslam/twin/osm.hpp"
#include "twinslam/twin/polygon_triangulation.hpp"

using namespace twinslam::twin;

// Delft: 570 city objects, 18262 vertices, EPSG:7415 (RD + NAP through the EGM96 fallback).
static void BM_CityJsonDelft(benchmark::State& state) {
  LoadOptions options;
  options.origin = {52.0, 4.36, 43.0};
  std::size_t triangles = 0;
  for (auto _ : state) {
    const CityJsonModel m = load_cityjson(std::string(TWINSLAM_SHARED_DIR) + "/data/cityjson/delft.json", options);
    triangles = m.mesh_W.num_triangles();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_CityJsonDelft)->Unit(benchmark::kMillisecond);

// One RD New + NAP point to WGS84 (horizontal operation + EGM96 geoid lookup).
static void BM_CrsRdNapPoint(benchmark::State& state) {
  const CrsTransform crs("EPSG:7415");
  double x = 85000.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(crs.to_lla({x, 447500.0, 5.0}));
    x += 0.001;
  }
}
BENCHMARK(BM_CrsRdNapPoint);

// A wall with N windows (each a 4-vertex hole) in a 3D plane: the bridging + ear clipping cost grows ~ n^2.
static void BM_TriangulateWallWithWindows(benchmark::State& state) {
  const int windows = static_cast<int>(state.range(0));
  std::vector<Eigen::Vector3d> points{{0, 0, 0}, {2.0 * windows + 1, 0, 0}, {2.0 * windows + 1, 0, 4}, {0, 0, 4}};
  std::vector<std::vector<int>> rings{{0, 1, 2, 3}};
  for (int w = 0; w < windows; ++w) {
    const int first = static_cast<int>(points.size());
    for (const auto& [x, z] : std::vector<std::pair<double, double>>{{1, 1}, {1, 3}, {2, 3}, {2, 1}})
      points.emplace_back(2.0 * w + x, 0.0, z);
    rings.push_back({first, first + 1, first + 2, first + 3});
  }
  for (auto _ : state) benchmark::DoNotOptimize(triangulate_polygon(points, rings));
  state.SetComplexityN(windows);
}
BENCHMARK(BM_TriangulateWallWithWindows)->RangeMultiplier(4)->Range(1, 256)->Complexity();

// An OSM XML file of N x N 12-node (L-shaped + notched) buildings on a 20 m grid.
static void BM_OsmBlocks(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("bench_twin_formats_" + std::to_string(::getpid()) + ".osm")).string();
  {
    std::ostringstream nodes, ways;
    nodes.precision(10);
    long long id = 1;
    const double outline[12][2] = {{0, 0}, {12, 0}, {12, 4}, {8, 4}, {8, 8}, {12, 8}, {12, 12}, {4, 12}, {4, 6},
                                   {2, 6}, {2, 12}, {0, 12}};
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        ways << "<way id=\"" << i * n + j + 1 << "\">";
        const long long first = id;
        for (const auto& p : outline) {
          nodes << "<node id=\"" << id << "\" lat=\"" << 47.0 + (20.0 * j + p[1]) / 111195.0 << "\" lon=\""
                << 8.0 + (20.0 * i + p[0]) / 75800.0 << "\"/>\n";
          ways << "<nd ref=\"" << id++ << "\"/>";
        }
        ways << "<nd ref=\"" << first << "\"/><tag k=\"building\" v=\"yes\"/><tag k=\"height\" v=\"15\"/></way>\n";
      }
    std::ofstream(path) << "<osm version=\"0.6\">\n" << nodes.str() << ways.str() << "</osm>\n";
  }
  LoadOptions options;
  options.origin = {47.0, 8.0, 400.0};
  for (auto _ : state) benchmark::DoNotOptimize(load_osm(path, options));
  std::filesystem::remove(path);
  state.counters["buildings"] = n * n;
}
BENCHMARK(BM_OsmBlocks)->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);
