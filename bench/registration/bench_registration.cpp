// Cost of one registration per keyframe against the size of the city (issue 12 targets: all-in time, >= 10x faster
// than the paper code's recipe, time and memory on 25 km^2 at most 1.2x those on 1 km^2).
// For each city (the simulator's procedural city, scenario city-loops, side 1 km and 5 km): the twin store is built
// once (untimed); keyframes along the flight get 150-1500 landmarks sampled on the twin's surfaces facing the camera
// within 50 m (facades weighted 3x over ground and roofs; no occlusion test), 0.1 m noise, 10 % outliers, seen through
// a drift of up to 0.5 m and 1 deg. A fresh child process (`--serve DIR ours`) then runs, per keyframe, the service's
// path: tiles arrive as the tiles service streams them (250 m window) into a WindowedTwin, whose update builds the
// tiles entering the 150 m window and one tile of its prefetch ring and drops those leaving; then
// register_cloud (preprocess, ICP, information). A second child (`--serve DIR pcl N`) runs the paper code's recipe on
// N of the same keyframes: +-350 m crop, KD-tree rebuilt per call, PCL IterativeClosestPointWithNormals, 25
// iterations, 8 m max correspondence distance. A third (`--serve DIR probe N`) compares the index's structure with a
// voxel hash (index_probe.cpp).
// Usage: bench_registration [--sizes 1000,5000] [--spacing M] [--keyframes K] [--pcl-keyframes N] [--threads T]
//        [--keep DIR]   (T: RegistrationConfig::threads of ours; the PCL recipe runs as PCL configures itself)
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "keyframes.hpp"
#include "twinslam/registration/registration.hpp"
#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/twin.hpp"

namespace {

namespace fs = std::filesystem;
using namespace twinslam;
using namespace twinslam::registration;
using bench::Keyframe;
using Clock = std::chrono::steady_clock;

// Landmarks a camera at p_W would triangulate: points on surfaces facing it within 50 m, noisy, with outliers.
std::vector<Eigen::Vector3d> sample_view(const sim::TriMesh& mesh, const Eigen::Vector3d& p_W, std::mt19937& rng) {
  std::vector<std::size_t> tri;
  std::vector<double> weight;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    const Eigen::Vector3d a = mesh.p_W[f[0]], b = mesh.p_W[f[1]], c = mesh.p_W[f[2]];
    Eigen::AlignedBox3d box(a);
    box.extend(b).extend(c);
    if (box.exteriorDistance(p_W) > 50.0) continue;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9 || n.dot(p_W - a) <= 0.0) continue;  // facing away
    const double area = std::min(0.5 * n.norm(), 7850.0);    // at most the 50 m disc
    tri.push_back(t);
    weight.push_back(area * (std::abs(n.normalized().z()) < 0.3 ? 3.0 : 1.0));
  }
  std::vector<Eigen::Vector3d> out;
  if (tri.empty()) return out;
  std::discrete_distribution<std::size_t> pick(weight.begin(), weight.end());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.1);
  const int wanted = std::uniform_int_distribution<int>(150, 1500)(rng);
  for (int tries = 0; static_cast<int>(out.size()) < wanted && tries < 200 * wanted; ++tries) {
    const auto& f = mesh.triangles[tri[pick(rng)]];
    double s = u(rng), t = u(rng);
    if (s + t > 1.0) s = 1.0 - s, t = 1.0 - t;
    const Eigen::Vector3d q =
        mesh.p_W[f[0]] + s * (mesh.p_W[f[1]] - mesh.p_W[f[0]]) + t * (mesh.p_W[f[2]] - mesh.p_W[f[0]]);
    if ((q - p_W).norm() > 50.0) continue;
    out.push_back(q + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  std::uniform_real_distribution<double> box(-30.0, 30.0);
  for (std::size_t k = 0, n = out.size() / 9; k < n; ++k)
    out.push_back(p_W + Eigen::Vector3d(box(rng), box(rng), box(rng)));
  return out;
}

Eigen::Isometry3d random_drift(const Eigen::Vector3d& pivot, std::mt19937& rng) {
  std::uniform_real_distribution<double> h(-0.5, 0.5), v(-0.2, 0.2), yaw(-1.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw(rng) * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = pivot + Eigen::Vector3d(h(rng), h(rng), v(rng)) - T.linear() * pivot;
  return T;
}

// Builds the city and its store in dir/twin, writes dir/keyframes.bin; returns the store build time [s].
double prepare(double size_m, double spacing_m, int keyframes, const fs::path& dir, std::size_t& tiles) {
  const auto t0 = Clock::now();
  sim::Scenario scenario = sim::builtin_scenario("city-loops");
  scenario.city.size_m = size_m;
  const sim::City city = sim::build_city(scenario.city, scenario.seed);
  const sim::Twin twin = sim::derive_twin(city, scenario.twin, scenario.seed);
  const sim::FlightTrajectory trajectory = sim::make_flight_trajectory(scenario, city.hints);
  twin::Mesh mesh_W;
  mesh_W.p_W = twin.mesh.p_W;
  mesh_W.triangles = twin.mesh.triangles;
  twin::StoreConfig store;
  store.point_spacing_m = spacing_m;
  const auto& o = scenario.origin;
  tiles = twin::build_twin_store(mesh_W, {o.lat_deg, o.lon_deg, o.alt_m}, store, (dir / "twin").string()).tiles.size();
  const double build_s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::mt19937 rng(7);
  std::vector<Keyframe> kfs;
  for (int k = 0; k < keyframes; ++k) {
    Keyframe kf;
    kf.p_WB_true = trajectory.at(trajectory.duration() * (k + 0.5) / keyframes).p_W;
    kf.drift = random_drift(kf.p_WB_true, rng);
    for (const auto& p : sample_view(twin.mesh, kf.p_WB_true, rng)) kf.p_guess_W.push_back(kf.drift * p);
    kfs.push_back(std::move(kf));
  }
  bench::write_keyframes((dir / "keyframes.bin").string(), kfs);
  return build_s;
}

struct Row {
  double size_m = 0, build_s = 0;
  std::size_t tiles = 0;
  double ours[15] = {};  // see serve_ours
  double pcl[4] = {};    // see serve_pcl
  double probe[6] = {};  // see serve_probe
};

template <std::size_t N>
void child(const std::string& args, double (&out)[N]) {
  const std::string cmd = fs::read_symlink("/proc/self/exe").string() + " --serve " + args;
  FILE* f = ::popen(cmd.c_str(), "r");
  for (double& x : out) {
    if (f == nullptr || std::fscanf(f, "%lf", &x) != 1) {
      std::fprintf(stderr, "bench_registration: '%s' failed\n", cmd.c_str());
      std::exit(1);
    }
  }
  ::pclose(f);
}

void print(const std::vector<Row>& rows, double spacing_m, int threads) {
  std::printf(
      "registration per keyframe (city-loops, 150 m window of 50 m tiles, twin point spacing %.1f m, "
      "150-1500 landmarks, 0.1 m noise, 10 %% outliers, drift <= 0.5 m / 1 deg; %d thread(s))\n\n",
      spacing_m, threads);
  std::printf(
      "| city | tiles | keyframes | accepted | all-in median [ms] | all-in p99 [ms] | index update median / p99 "
      "[ms] | preprocess [ms] | ICP [ms] | Hessian [ms] | position error median [m] | index [MB] | RSS growth "
      "[MB] | PCL recipe median [ms] (crop points) | PCL error median [m] | ratio PCL / ours |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    const double* o = r.ours;
    std::printf(
        "| %.0f km^2 | %zu | %.0f | %.0f | %.2f | %.2f | %.2f / %.2f | %.2f | %.2f | %.3f | %.3f | %.1f | %.1f "
        "| %.0f (%.0f) | %.3f | %.0f |\n",
        r.size_m * r.size_m / 1e6, r.tiles, o[0], o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10], o[11],
        r.pcl[0], r.pcl[2], r.pcl[3], r.pcl[0] / o[2]);
  }
  std::printf("\ntwin index structure on the same windows (20 keyframes, radius 1 m, the keyframes' landmarks):\n\n");
  std::printf(
      "| city | build per tile: KD-tree / voxel hash [ms] | query: KD-tree / voxel hash [us] | found | "
      "mismatches |\n|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %.0f km^2 | %.2f / %.2f | %.2f / %.2f | %.2f | %.0f |\n", r.size_m * r.size_m / 1e6, r.probe[0],
                r.probe[1], r.probe[2], r.probe[3], r.probe[4], r.probe[5]);
  }
  std::printf(
      "\nICP work per keyframe (the flights differ between cities, so do the views):\n\n| city | source points "
      "median | iterations median | ICP per point and association [us] |\n|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %.0f km^2 | %.0f | %.0f | %.3f |\n", r.size_m * r.size_m / 1e6, r.ours[12], r.ours[13], r.ours[14]);
  }
  if (rows.size() >= 2) {
    const Row &a = rows.front(), &b = rows.back();
    std::printf(
        "\nratio last/first city: all-in median %.2f, p99 %.2f, ICP per point and association %.2f, RSS growth "
        "%.2f (target <= 1.2)\n",
        b.ours[2] / a.ours[2], b.ours[3] / a.ours[3], b.ours[14] / a.ours[14], b.ours[11] / std::max(a.ours[11], 1e-9));
  }
}

std::vector<double> parse_list(const std::string& list) {
  std::vector<double> v;
  for (std::size_t p = 0; p < list.size();) {
    const std::size_t q = std::min(list.find(',', p), list.size());
    v.push_back(std::stod(list.substr(p, q - p)));
    p = q + 1;
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 4 && std::string(argv[1]) == "--serve") {
    const std::string mode = argv[3];
    const int n = argc >= 5 ? std::stoi(argv[4]) : 10;
    if (mode == "probe") return bench::serve_probe(argv[2], n);
    return mode == "ours" ? bench::serve_ours(argv[2], n) : bench::serve_pcl(argv[2], n);
  }
  double spacing_m = 1.0;
  int keyframes = 150, pcl_keyframes = 10, threads = 1;
  std::vector<double> sizes{1000, 5000};
  std::string keep;  // --keep DIR: leave the cities' stores and keyframes there (profiling: --serve DIR/1000 ours)
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--sizes")
      sizes = parse_list(value);
    else if (flag == "--spacing")
      spacing_m = std::stod(value);
    else if (flag == "--keyframes")
      keyframes = std::stoi(value);
    else if (flag == "--pcl-keyframes")
      pcl_keyframes = std::stoi(value);
    else if (flag == "--threads")
      threads = std::stoi(value);
    else if (flag == "--keep")
      keep = value;
    else {
      std::fprintf(stderr,
                   "usage: bench_registration [--sizes S,S] [--spacing M] [--keyframes K] [--pcl-keyframes N] "
                   "[--threads T] [--keep DIR]\n");
      return 2;
    }
  }
  const fs::path root = keep.empty()
                            ? fs::temp_directory_path() / ("twinslam_bench_registration_" + std::to_string(::getpid()))
                            : fs::path(keep);
  std::vector<Row> rows;
  for (double s : sizes) {
    const fs::path dir = root / std::to_string(static_cast<int>(s));
    Row r;
    r.size_m = s;
    r.build_s = prepare(s, spacing_m, keyframes, dir, r.tiles);
    std::fprintf(stderr, "city %.0f m: store %.1f s, %zu tiles\n", s, r.build_s, r.tiles);
    child(dir.string() + " ours " + std::to_string(threads), r.ours);
    child(dir.string() + " pcl " + std::to_string(pcl_keyframes), r.pcl);
    child(dir.string() + " probe 20", r.probe);
    rows.push_back(r);
    if (keep.empty()) fs::remove_all(dir);  // disk space: one city at a time
  }
  if (keep.empty()) fs::remove_all(root);
  print(rows, spacing_m, threads);
  return 0;
}
