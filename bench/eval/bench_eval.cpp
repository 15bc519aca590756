// bench_eval: one full `twinslam eval` computation (no file I/O) on a 6000-pose trajectory, about 5 min at 20 Hz
// over ~600 m: association, sim3 alignment, ATE, RPE at 8 segment lengths. Issue 4 asks for < 1 s.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "twinslam/eval/evaluate.hpp"

namespace {

using twinslam::StampedPose;
using twinslam::Trajectory;

// Ground truth at 200 Hz (as EuRoC), the estimate at 20 Hz with a 3 ms stamp offset, noise and a similarity.
void make_inputs(std::size_t n_est, Trajectory& gt, Trajectory& est) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  const std::size_t n_gt = 10 * n_est;
  for (std::size_t k = 0; k < n_gt; ++k) {
    const double t = static_cast<double>(k) * 0.005;  // [s]
    StampedPose p;
    p.stamp_ns = static_cast<std::int64_t>(k) * 5'000'000;
    p.T_XB.translation() = Eigen::Vector3d(40.0 * std::cos(0.05 * t), 40.0 * std::sin(0.05 * t), 5.0 + 0.02 * t);
    p.T_XB.linear() = Eigen::AngleAxisd(0.05 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    gt.poses.push_back(p);
  }
  const Eigen::Matrix3d R_LW = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (std::size_t k = 0; k < n_est; ++k) {
    StampedPose p = gt.poses[10 * k];
    p.stamp_ns += 3'000'000;
    p.T_XB.translation() = 0.8 * R_LW * p.T_XB.translation() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    p.T_XB.linear() = R_LW * p.T_XB.linear();
    est.poses.push_back(p);
  }
}

void BM_EvalSim3(benchmark::State& state) {
  Trajectory gt, est;
  make_inputs(static_cast<std::size_t>(state.range(0)), gt, est);
  twinslam::eval::EvalConfig config;
  config.align = twinslam::eval::AlignMode::Sim3;
  for (auto _ : state) {
    const auto r = twinslam::eval::evaluate(gt, est, config);
    benchmark::DoNotOptimize(r.ate.pos.rmse);
  }
  state.counters["poses"] = static_cast<double>(est.size());
}
BENCHMARK(BM_EvalSim3)->Arg(6000)->Unit(benchmark::kMillisecond);

}  // namespace
