// Cost of the tiles service against the size of the city (issue 7 target: 25 km^2 costs at most 1.2x what 1 km^2
// costs). For a 1 km x 1 km and a 5 km x 5 km procedural city: the twin store is built once (not timed as service
// cost), then the service's pure part runs the city-loops flight at 20 Hz — TileStreamer::update for every pose and
// TileCache::get (disk read on a miss) for every tile to publish — and the table reports the time per update and
// the memory the service holds: its accounted bytes (index + grid + per-vehicle sets + cached tiles) and the growth of
// the resident set of a fresh process from before the index was read to after the first flight.
// Usage: bench_tiles [--spacing M] [--sizes 1000,5000]   (M: store point spacing, default 2 m)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <malloc.h>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include "city_twin_fixture.hpp"
#include "twinslam/tiles/tile_cache.hpp"
#include "twinslam/tiles/tile_streamer.hpp"

namespace {

namespace fs = std::filesystem;
using namespace twinslam;
using Clock = std::chrono::steady_clock;

double rss_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

struct Row {
  double size_m = 0;
  std::size_t tiles = 0, updates = 0, published = 0;
  double build_s = 0;
  double update_us_mean = 0, update_us_p99 = 0;   // TileStreamer::update only
  double total_us_mean = 0;                       // update + cache reads of the tiles to publish
  double index_mb = 0, cache_mb = 0, accounted_mb = 0, rss_growth_mb = 0;
};

// The service part, in a fresh process (`--serve DIR`) so the resident set is not blurred by the city build's freed
// heap: reads the index, flies the positions in DIR/positions.bin five times (a fresh streamer each pass, one cache),
// prints one line of numbers.
int serve(const fs::path& dir) {
  std::vector<Eigen::Vector3d> positions;
  {
    std::ifstream in(dir / "positions.bin", std::ios::binary);
    Eigen::Vector3d p;
    while (in.read(reinterpret_cast<char*>(p.data()), sizeof(double) * 3)) positions.push_back(p);
  }
  const std::string twin_dir = (dir / "twin").string();
  const double rss0 = rss_mb();
  std::optional<tiles::TileStreamer> streamer;
  tiles::TileCache cache(64, tiles::TileCache::store_loader(twin_dir));
  std::vector<double> update_us;
  double total_us = 0, rss_growth = 0;
  for (int pass = 0; pass < 5; ++pass) {
    streamer.emplace(twin::read_twin_index(twin_dir), 150.0);
    ::malloc_trim(0);  // the index.json parse is transient: give its heap back, as a long-running service would
    for (const Eigen::Vector3d& p_W : positions) {
      const auto a = Clock::now();
      const tiles::StreamDecision d = streamer->update("uav0", p_W);
      const auto b = Clock::now();
      for (const auto& key : d.publish) cache.get(*streamer->grid().find(key));
      const auto c = Clock::now();
      update_us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
      total_us += std::chrono::duration<double, std::micro>(c - a).count();
    }
    if (pass == 0) rss_growth = rss_mb() - rss0;
  }
  double sum = 0;
  for (double u : update_us) sum += u;
  const double mean = sum / static_cast<double>(update_us.size());
  std::sort(update_us.begin(), update_us.end());
  const double mb = 1024.0 * 1024.0;
  std::printf("%zu %zu %.4f %.4f %.4f %.6f %.6f %.6f %.4f\n", positions.size(), streamer->published_count(), mean,
              update_us[update_us.size() * 99 / 100], total_us / static_cast<double>(update_us.size()),
              static_cast<double>(streamer->grid().memory_bytes()) / mb, static_cast<double>(cache.bytes()) / mb,
              static_cast<double>(streamer->memory_bytes() + cache.bytes()) / mb, rss_growth);
  return 0;
}

Row run(double size_m, double spacing_m, const fs::path& dir) {
  Row row;
  row.size_m = size_m;
  const auto t0 = Clock::now();
  {
    const tiles::test::CityTwin city = tiles::test::make_city_twin("city-loops", size_m, dir / "twin", spacing_m);
    row.build_s = std::chrono::duration<double>(Clock::now() - t0).count();
    row.tiles = city.index.tiles.size();
    std::ofstream out(dir / "positions.bin", std::ios::binary);
    for (int k = 0; k / 20.0 <= city.trajectory.duration(); ++k) {
      const Eigen::Vector3d p_W = city.trajectory.at(k / 20.0).p_W;
      out.write(reinterpret_cast<const char*>(p_W.data()), sizeof(double) * 3);
    }
  }
  const std::string cmd = fs::read_symlink("/proc/self/exe").string() + " --serve " + dir.string();
  FILE* child = ::popen(cmd.c_str(), "r");
  if (child == nullptr || std::fscanf(child, "%zu %zu %lf %lf %lf %lf %lf %lf %lf", &row.updates, &row.published,
                                      &row.update_us_mean, &row.update_us_p99, &row.total_us_mean, &row.index_mb,
                                      &row.cache_mb, &row.accounted_mb, &row.rss_growth_mb) != 9) {
    std::fprintf(stderr, "bench_tiles: '%s' failed\n", cmd.c_str());
    std::exit(1);
  }
  ::pclose(child);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  double spacing_m = 2.0;
  std::vector<double> sizes{1000, 5000};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--serve") return serve(argv[i + 1]);
    if (flag == "--spacing") {
      spacing_m = std::stod(argv[i + 1]);
    } else if (flag == "--sizes") {
      sizes.clear();
      std::string list = argv[i + 1];
      for (std::size_t p = 0; p < list.size();) {
        const std::size_t q = std::min(list.find(',', p), list.size());
        sizes.push_back(std::stod(list.substr(p, q - p)));
        p = q + 1;
      }
    } else {
      std::fprintf(stderr, "usage: bench_tiles [--spacing M] [--sizes S,S,...]\n");
      return 2;
    }
  }
  const fs::path root = fs::temp_directory_path() / ("twinslam_bench_tiles_" + std::to_string(::getpid()));
  std::vector<Row> rows;
  for (double s : sizes) {
    rows.push_back(run(s, spacing_m, root / std::to_string(static_cast<int>(s))));
    fs::remove_all(root / std::to_string(static_cast<int>(s)));  // disk space: one city at a time
  }
  fs::remove_all(root);
  std::printf("tiles service cost vs city size (city-loops flight at 20 Hz, 150 m window, 50 m tiles, cache 64, "
              "point spacing %.1f m)\n\n", spacing_m);
  std::printf("| city | tiles | updates x5 | published | store build [s] | update mean [us] | update p99 [us] | "
              "update+cache mean [us] | index+grid [MB] | cache [MB] | accounted [MB] | RSS growth [MB] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %.0f km^2 | %zu | %zu | %zu | %.1f | %.2f | %.2f | %.1f | %.3f | %.3f | %.3f | %.2f |\n",
                r.size_m * r.size_m / 1e6, r.tiles, r.updates, r.published, r.build_s, r.update_us_mean,
                r.update_us_p99, r.total_us_mean, r.index_mb, r.cache_mb, r.accounted_mb, r.rss_growth_mb);
  }
  if (rows.size() >= 2) {
    const Row& a = rows.front();
    const Row& b = rows.back();
    std::printf("\nratio last/first: update mean %.2f, update+cache %.2f, accounted memory %.2f, RSS growth %.2f "
                "(target <= 1.2)\n", b.update_us_mean / a.update_us_mean, b.total_us_mean / a.total_us_mean,
                b.accounted_mb / a.accounted_mb, b.rss_growth_mb / std::max(a.rss_growth_mb, 1e-9));
  }
  return 0;
}
