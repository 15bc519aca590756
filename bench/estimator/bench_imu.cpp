// Cost of preintegrating 200 IMU samples and of one ImuFactor evaluation with all four Jacobians.
#include <memory>

#include <benchmark/benchmark.h>

#include "imu_test_utils.hpp"
#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/estimator/preintegration.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;

namespace {

// 201 samples at 200 Hz covering [0, 1 s]: 200 integration steps.
const std::vector<est::ImuSample>& samples() {
  static const auto s = ts::simulate_imu(ts::AnalyticTrajectory{}, 0, 1'000'000'000, 200.0);
  return s;
}

void BM_Preintegrate200(benchmark::State& state) {
  est::PreintegrationConfig config;
  config.integration = state.range(0) == 0 ? est::ImuIntegration::kMidpoint : est::ImuIntegration::kEuler;
  for (auto _ : state) {
    est::Preintegration pre(config, {}, samples(), 0, 1'000'000'000);
    benchmark::DoNotOptimize(pre.delta().p.data());
  }
  state.SetLabel(state.range(0) == 0 ? "midpoint" : "euler");
  state.SetItemsProcessed(state.iterations() * 200);
}
BENCHMARK(BM_Preintegrate200)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_ImuFactorEvaluateWithJacobians(benchmark::State& state) {
  const ts::AnalyticTrajectory traj;
  const auto pre = std::make_shared<est::Preintegration>(est::PreintegrationConfig{}, est::ImuBias{}, samples(),
                                                         100'000'000, 600'000'000);
  const est::ImuFactor factor(pre);
  double pose_i[7], sb_i[9], pose_j[7], sb_j[9];
  est::pack(ts::true_state(traj, 100'000'000), pose_i, sb_i);
  est::pack(ts::true_state(traj, 600'000'000), pose_j, sb_j);
  pose_j[0] += 0.01;  // a non-zero residual, like during a solve
  const double* params[4] = {pose_i, sb_i, pose_j, sb_j};
  double residual[15], j0[15 * 7], j1[15 * 9], j2[15 * 7], j3[15 * 9];
  double* jacobians[4] = {j0, j1, j2, j3};
  for (auto _ : state) {
    factor.Evaluate(params, residual, jacobians);
    benchmark::DoNotOptimize(residual);
    benchmark::DoNotOptimize(j3);
  }
}
BENCHMARK(BM_ImuFactorEvaluateWithJacobians)->Unit(benchmark::kNanosecond);

}  // namespace
