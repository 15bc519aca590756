#pragma once
// Benchmark keyframes: what the estimator would hand the registration along the scenario's flight, written by the
// parent process and read by the measuring child (a fresh process, so its resident set is the registration's own).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Geometry>

namespace twinslam::registration::bench {

struct Keyframe {
  Eigen::Vector3d p_WB_true = Eigen::Vector3d::Zero();      // true body position [m, W]
  Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();  // the estimate's error: p_guess = drift * p_true
  std::vector<Eigen::Vector3d> p_guess_W;                   // landmarks as the estimator sees them (T_WL = identity)
};

inline void write_keyframes(const std::string& path, const std::vector<Keyframe>& kfs) {
  FILE* f = std::fopen(path.c_str(), "wb");
  const std::size_t n = kfs.size();
  std::fwrite(&n, sizeof n, 1, f);
  for (const Keyframe& k : kfs) {
    const std::size_t m = k.p_guess_W.size();
    std::fwrite(k.p_WB_true.data(), sizeof(double), 3, f);
    std::fwrite(k.drift.matrix().data(), sizeof(double), 16, f);
    std::fwrite(&m, sizeof m, 1, f);
    for (const auto& p : k.p_guess_W) std::fwrite(p.data(), sizeof(double), 3, f);
  }
  std::fclose(f);
}

inline std::vector<Keyframe> read_keyframes(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  std::size_t n = 0;
  std::vector<Keyframe> kfs;
  if (f == nullptr || std::fread(&n, sizeof n, 1, f) != 1) return kfs;
  kfs.resize(n);
  for (Keyframe& k : kfs) {
    std::size_t m = 0;
    bool ok = std::fread(k.p_WB_true.data(), sizeof(double), 3, f) == 3;
    ok = ok && std::fread(k.drift.matrix().data(), sizeof(double), 16, f) == 16;
    ok = ok && std::fread(&m, sizeof m, 1, f) == 1;
    k.p_guess_W.resize(ok ? m : 0);
    for (auto& p : k.p_guess_W) ok = ok && std::fread(p.data(), sizeof(double), 3, f) == 3;
  }
  std::fclose(f);
  return kfs;
}

// The paper code's recipe, in pcl_baseline.cpp (the only TU with PCL's registration headers): crop +-crop_half_m of
// the twin's points around the keyframe, build a KD-tree over the crop (inside PCL), IterativeClosestPointWithNormals
// for `iterations` with `max_corr_m`. Returns the wall time [ms]; p_corrected gets the corrected body position.
struct PclBaseline {
  struct Impl;
  explicit PclBaseline(const std::string& twin_dir);
  ~PclBaseline();
  double run(const Keyframe& k, double crop_half_m, int iterations, double max_corr_m, Eigen::Vector3d& p_corrected,
             std::size_t& crop_points);
  Impl* impl;
};

inline double rss_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

inline double pct(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

// The measuring children (serve.cpp): each prints one line of numbers on stdout.
int serve_ours(const std::string& dir, int threads);  // threads: RegistrationConfig::threads
int serve_pcl(const std::string& dir, int keyframes);
int serve_probe(const std::string& dir, int keyframes);  // index_probe.cpp

}  // namespace twinslam::registration::bench
