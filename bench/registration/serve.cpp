// The measuring children of bench_registration (a fresh process each, so the resident set is the registration's).
#include <malloc.h>
#include <chrono>
#include <cstdio>
#include <set>

#include "keyframes.hpp"
#include "twinslam/registration/registration.hpp"
#include "twinslam/registration/windowed_twin.hpp"

namespace twinslam::registration::bench {
namespace {

using Clock = std::chrono::steady_clock;
double ms(Clock::time_point a) { return std::chrono::duration<double, std::milli>(Clock::now() - a).count(); }

// What the tiles service does for the registration: every tile of its window (250 m, tiles_config.hpp) around the
// vehicle is sent once; the registration keeps it compressed (WindowedTwin). Returns the time of taking them in [ms]
// (the file reads, the tiles service's part, are not counted).
double receive_tiles(WindowedTwin& twin, const twin::TwinIndex& store, const std::string& dir, const Eigen::Vector3d& p,
                     std::set<twin::TileKey>& sent) {
  double ms_in = 0.0;
  for (const twin::TileKey& k : tiles_in_window(store, p, 250.0)) {
    if (!sent.insert(k).second) continue;
    std::vector<std::uint8_t> bytes = twin::read_tile_file(dir, k, true);
    const auto t0 = Clock::now();
    twin.add_tile(k, store.find(k)->bounds_W, std::move(bytes));
    ms_in += ms(t0);
  }
  return ms_in;
}

}  // namespace

// Prints: keyframes, accepted, all-in median, p99, index-update median, p99, preprocess, ICP, Hessian medians [ms],
// median position error of accepted keyframes [m], index memory (largest) [MB], RSS growth [MB], medians of source
// points, ICP iterations and ICP time per point and association (iterations + the final one) [us].
int serve_ours(const std::string& dir, int threads) {
  const std::vector<Keyframe> kfs = read_keyframes(dir + "/keyframes.bin");
  const std::string twin_dir = dir + "/twin";
  // The registration service gets tiles over DDS and never reads the store's index: it is read (and its parse heap
  // returned) before the baseline of the resident set.
  const twin::TwinIndex store = twin::read_twin_index(twin_dir);
  ::malloc_trim(0);
  const double rss0 = rss_mb();
  RegistrationConfig config;
  config.threads = threads;
  // The service's defaults (registration_node.hpp; the library's are the same): 50 m prefetch ring, one ring tile per
  // update, indexed tiles kept 50 m beyond the ring.
  WindowedTwin windowed(store.tile_size_m, 150.0);
  const TwinTileIndex& index = windowed.index();
  std::set<twin::TileKey> sent;
  std::vector<double> all, upd, pre, icp, hes, err, pts, its, per;
  double index_mb = 0;
  for (const Keyframe& k : kfs) {
    const Eigen::Vector3d c = k.drift * k.p_WB_true;
    const double in_ms = receive_tiles(windowed, store, twin_dir, c, sent);
    upd.push_back(in_ms + windowed.update("bench", c).update_ms);
    SourceInput in;
    for (const auto& p : k.p_guess_W) in.landmarks.push_back({p, 1.0});
    in.T_LB.translation() = c;
    const RegistrationResult r = register_cloud(config, index, in);
    all.push_back(upd.back() + r.time.total_ms);
    pre.push_back(r.time.preprocess_ms);
    icp.push_back(r.time.icp_ms);
    hes.push_back(r.time.hessian_ms);
    pts.push_back(static_cast<double>(r.source_points));
    its.push_back(r.iterations);
    per.push_back(1e3 * r.time.icp_ms / std::max(1.0, static_cast<double>(r.source_points * (r.iterations + 1))));
    if (r.accepted()) err.push_back((r.correction_W * c - k.p_WB_true).norm());
    index_mb = std::max(index_mb, static_cast<double>(index.memory_bytes()) / (1024.0 * 1024.0));
  }
  std::printf("%zu %zu %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.5f %.3f %.3f %.0f %.0f %.3f\n", kfs.size(), err.size(),
              pct(all, 0.5), pct(all, 0.99), pct(upd, 0.5), pct(upd, 0.99), pct(pre, 0.5), pct(icp, 0.5), pct(hes, 0.5),
              pct(err, 0.5), index_mb, rss_mb() - rss0, pct(pts, 0.5), pct(its, 0.5), pct(per, 0.5));
  return 0;
}

// Prints: PCL recipe median, p99 [ms], mean crop points, median position error [m] over n keyframes spread evenly.
int serve_pcl(const std::string& dir, int n) {
  const std::vector<Keyframe> kfs = read_keyframes(dir + "/keyframes.bin");
  PclBaseline pcl(dir + "/twin");
  std::vector<double> t, err;
  double crop = 0;
  for (int i = 0; i < n && !kfs.empty(); ++i) {
    const Keyframe& k = kfs[static_cast<std::size_t>(i) * kfs.size() / static_cast<std::size_t>(n)];
    Eigen::Vector3d p;
    std::size_t pts = 0;
    t.push_back(pcl.run(k, 350.0, 25, 8.0, p, pts));
    err.push_back((p - k.p_WB_true).norm());
    crop += static_cast<double>(pts) / n;
  }
  std::printf("%.3f %.3f %.0f %.5f\n", pct(t, 0.5), pct(t, 0.99), crop, pct(err, 0.5));
  return 0;
}

}  // namespace twinslam::registration::bench
