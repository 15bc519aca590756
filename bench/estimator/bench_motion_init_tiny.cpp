// Motion initialization on the `tiny` scenario over many seeds (issue 5: "within 3 s of motion on at least 19 of 20
// seeds"). For each seed: `twinslam sim --scenario tiny --features --no-images --seed S`, then the estimator is fed
// from START seconds on (the flight rests about 0.8 s at the start, so from 2 s it is in motion and only the motion
// initialization can start it); prints the time to initialize, the tilt and speed errors at that moment, and the
// ATE (posyaw) of the rest of the flight and the estimator's time per frame.
// Usage: bench_motion_init_tiny [SEEDS=20] [START_S=2.0]   or   bench_motion_init_tiny DATASET_DIR [START_S=0]
// (the second form runs one existing dataset with features.csv, e.g. city-loops, for the time per frame).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/eval/evaluate.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/features.hpp"
#include "twinslam/trajectory/io.hpp"

namespace fs = std::filesystem;
using namespace twinslam;
using namespace twinslam::estimator;

namespace {

struct SeedResult {
  bool initialized = false;
  double init_after_s = 0.0, tilt_err_deg = 0.0, speed_err_mps = 0.0, ate_m = 0.0, ate_deg = 0.0, length_m = 0.0;
  double median_ms = 0.0, p99_ms = 0.0;  // estimator time per frame once tracking
};

const StampedPose* nearest(const Trajectory& t, std::int64_t stamp_ns) {
  const StampedPose* best = nullptr;
  for (const auto& p : t.poses) {
    if (!best || std::llabs(p.stamp_ns - stamp_ns) < std::llabs(best->stamp_ns - stamp_ns)) best = &p;
  }
  return best;
}

SeedResult run_seed(const fs::path& dir, double start_s) {
  ingest::Dataset data;  // features-only: no images to list
  data.imu = ingest::load_imu_csv(dir / "mav0/imu0/data.csv");
  const CameraConfig camera = read_camera_sensor_yaml(dir / "mav0/cam0/sensor.yaml");
  const auto model = make_camera(camera.intrinsics);
  const auto frames = ingest::load_feature_tracks(dir / "mav0/cam0/features.csv");
  const Trajectory truth = read_dataset_groundtruth(dir);
  SlidingWindowConfig config;
  config.T_BC = camera.T_BC;
  config.focal_px = camera.intrinsics.fu;
  config.pixel_sigma = 0.5;
  config.imu = load_imu_noise(dir / "mav0/imu0/sensor.yaml");
  config.max_solver_time_s = 10.0;
  SlidingWindowEstimator est(config);
  const std::int64_t t_start = frames.front().stamp_ns + static_cast<std::int64_t>(start_s * 1e9);
  std::size_t imu_next = 0;
  while (imu_next < data.imu.size() && data.imu[imu_next].stamp_ns < t_start - 50'000'000) ++imu_next;
  SeedResult r;
  Trajectory estimate;
  std::vector<double> ms;
  for (const auto& f : frames) {
    if (f.stamp_ns < t_start) continue;
    while (imu_next < data.imu.size() && data.imu[imu_next].stamp_ns <= f.stamp_ns) {
      const auto& s = data.imu[imu_next++];
      est.add_imu({s.stamp_ns, s.gyro_radps, s.accel_mps2});
    }
    std::vector<FeatureBearing> features;
    for (const auto& o : f.features) {
      Eigen::Vector3d b;
      if (model->unproject(Eigen::Vector2d(o.u, o.v), &b)) features.push_back({static_cast<std::int64_t>(o.landmark_id), b.normalized()});
    }
    const FrameEstimate e = est.add_frame(f.stamp_ns, features);
    if (e.status != EstimatorStatus::kTracking) continue;
    if (!r.initialized) {
      r.initialized = true;
      r.init_after_s = 1e-9 * static_cast<double>(f.stamp_ns - t_start);
      const StampedPose* gt = nearest(truth, f.stamp_ns);
      const Eigen::Vector3d up_true = gt->T_XB.linear().transpose() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d up_est = e.T_LB.linear().transpose() * Eigen::Vector3d::UnitZ();
      r.tilt_err_deg = std::acos(std::min(1.0, up_true.dot(up_est))) * 180.0 / M_PI;
      const StampedPose* gt_next = nearest(truth, f.stamp_ns + 10'000'000);
      const double dt = 1e-9 * static_cast<double>(gt_next->stamp_ns - gt->stamp_ns);
      if (dt > 0) r.speed_err_mps = std::abs((gt_next->p_X() - gt->p_X()).norm() / dt - e.v_L.norm());
    }
    estimate.poses.push_back({f.stamp_ns, e.T_LB});
    ms.push_back(e.estimator_ms);
  }
  if (!ms.empty()) {
    std::sort(ms.begin(), ms.end());
    r.median_ms = ms[ms.size() / 2];
    r.p99_ms = ms[ms.size() * 99 / 100];
  }
  if (estimate.poses.size() > 10) {
    eval::EvalConfig ec;
    ec.align = eval::AlignMode::PosYaw;
    const eval::EvalResult ev = eval::evaluate(truth, estimate, ec);
    r.ate_m = ev.ate.pos.rmse;
    r.ate_deg = ev.ate.rot.rmse;
    r.length_m = ev.length_m;
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && fs::is_directory(argv[1])) {
    const SeedResult r = run_seed(argv[1], argc > 2 ? std::atof(argv[2]) : 0.0);
    std::printf("%s: initialized after %.2f s, ATE_p %.3f m over %.1f m (%.2f %%), ATE_R %.2f deg, estimator ms median "
                "%.2f p99 %.2f\n", argv[1], r.init_after_s, r.ate_m, r.length_m, 100.0 * r.ate_m / r.length_m,
                r.ate_deg, r.median_ms, r.p99_ms);
    return r.initialized ? 0 : 1;
  }
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const double start_s = argc > 2 ? std::atof(argv[2]) : 2.0;
  const fs::path exe = fs::path(TWINSLAM_BIN_DIR) / "twinslam";
  int ok = 0;
  std::printf("| seed | initialized after [s] | tilt error [deg] | speed error [m/s] | ATE_p [m] | ATE_R [deg] | path [m] | "
              "ms median | ms p99 |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int seed = 1; seed <= seeds; ++seed) {
    const fs::path dir = fs::temp_directory_path() / ("twinslam_mi_" + std::to_string(::getpid()) + "_" + std::to_string(seed));
    const std::string cmd = exe.string() + " sim --scenario tiny --features --no-images --quiet --seed " +
                            std::to_string(seed) + " --out " + dir.string() + " > /dev/null";
    if (std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "simulation failed: %s\n", cmd.c_str());
      return 1;
    }
    const SeedResult r = run_seed(dir, start_s);
    fs::remove_all(dir);
    const bool within = r.initialized && r.init_after_s <= 3.0;
    ok += within ? 1 : 0;
    if (r.initialized) {
      std::printf("| %d | %.2f | %.2f | %.3f | %.3f | %.2f | %.0f | %.1f | %.1f |\n", seed, r.init_after_s,
                  r.tilt_err_deg, r.speed_err_mps, r.ate_m, r.ate_deg, r.length_m, r.median_ms, r.p99_ms);
    } else {
      std::printf("| %d | never | | | | | |\n", seed);
    }
    std::fflush(stdout);
  }
  std::printf("\ninitialized within 3 s of motion: %d of %d seeds (feeding from %.1f s, in motion)\n", ok, seeds, start_s);
  return 0;
}
