// Costs of the visual side of the window: one ReprojectionFactor evaluation (per observation and solver iteration),
// triangulating a landmark, a 5-keyframe / 50-landmark visual-inertial bundle adjustment, and marginalizing its oldest
// keyframe.
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include "ba_problem.hpp"
#include "twinslam/estimator/marginalization.hpp"
#include "twinslam/estimator/triangulation.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;

namespace {

const ts::BaProblem& problem_data() {
  static const ts::BaProblem p = ts::make_ba_problem(5, 50, 51);
  return p;
}

void BM_ReprojectionFactorEvaluate(benchmark::State& state) {
  const auto& p = problem_data();
  ts::BaState s = ts::true_ba_state(p);
  const auto& lm = p.landmarks[0];
  const est::ReprojectionFactor factor(lm.f_Ca, lm.observations[0].f_C, p.T_BC, 460.0);
  s.pose[lm.observations[0].keyframe][0] += 0.01;  // a non-zero residual, like during a solve
  const double* params[3] = {s.pose[lm.anchor].data(), s.pose[lm.observations[0].keyframe].data(), &s.rho[0]};
  double residual[2], j0[14], j1[14], j2[2];
  double* jacobians[3] = {j0, j1, j2};
  const bool with_jacobians = state.range(0) == 1;
  for (auto _ : state) {
    factor.Evaluate(params, residual, with_jacobians ? jacobians : nullptr);
    benchmark::DoNotOptimize(residual);
    benchmark::DoNotOptimize(j2);
  }
  state.SetLabel(with_jacobians ? "with jacobians" : "residual only");
}
BENCHMARK(BM_ReprojectionFactorEvaluate)->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);

void BM_Triangulate(benchmark::State& state) {
  const auto& p = problem_data();
  std::vector<est::BearingObservation> obs;
  const auto& lm = p.landmarks[0];
  const auto pose = [&](int k) { return twinslam::geometry::make_pose(p.truth[k].q_LB, p.truth[k].p_L); };
  obs.push_back({pose(lm.anchor), lm.f_Ca});
  for (const auto& o : lm.observations) obs.push_back({pose(o.keyframe), o.f_C});
  for (auto _ : state) {
    const auto result = est::triangulate(est::TriangulationConfig{}, obs, p.T_BC);
    benchmark::DoNotOptimize(result.rho);
  }
  state.SetLabel(std::to_string(obs.size()) + " views");
}
BENCHMARK(BM_Triangulate)->Unit(benchmark::kNanosecond);

// Full solve from the perturbed start of the test (about 5 cm / 1 deg), DENSE_SCHUR, one thread.
void BM_BundleAdjustmentSolve(benchmark::State& state) {
  const auto& p = problem_data();
  std::mt19937 rng(52);
  const ts::BaState start = ts::perturbed_ba_state(p, rng);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = static_cast<int>(state.range(0));
  options.num_threads = 1;
  std::size_t iterations = 0, residual_blocks = 0;
  for (auto _ : state) {
    state.PauseTiming();
    ts::BaState s = start;
    auto problem = std::make_unique<ceres::Problem>();
    ts::add_ba_to_problem(p, s, *problem);
    state.ResumeTiming();
    ceres::Solver::Summary summary;
    ceres::Solve(options, problem.get(), &summary);
    iterations = summary.iterations.size();
    residual_blocks = static_cast<std::size_t>(summary.num_residual_blocks);
    state.PauseTiming();
    problem.reset();
    state.ResumeTiming();
  }
  state.SetLabel(std::to_string(iterations) + " iterations, " + std::to_string(residual_blocks) + " factors");
}
BENCHMARK(BM_BundleAdjustmentSolve)->Arg(5)->Arg(50)->Unit(benchmark::kMillisecond);

// Marginalizing keyframe 0 (pose, speed/bias, the landmarks anchored there) at the true state.
void BM_MarginalizeOldestKeyframe(benchmark::State& state) {
  const auto& p = problem_data();
  ts::BaState s = ts::true_ba_state(p);
  ceres::Problem problem;
  ts::add_ba_to_problem(p, s, problem, {}, false);
  std::vector<double*> marginalized{s.pose[0].data(), s.speed_bias[0].data()};
  for (std::size_t i = 0; i < p.landmarks.size(); ++i) {
    if (p.landmarks[i].anchor == 0) marginalized.push_back(&s.rho[i]);
  }
  est::Marginalizer marginalizer;
  const auto factors = marginalizer.add_connected(problem, marginalized).size();
  int tangent = 0;
  for (auto _ : state) {
    const auto prior = marginalizer.marginalize();
    tangent = prior->tangent_size();
    benchmark::DoNotOptimize(prior.get());
  }
  state.SetLabel(std::to_string(factors) + " factors, " + std::to_string(marginalized.size()) + " blocks out, prior on " +
                 std::to_string(tangent) + " dims");
}
BENCHMARK(BM_MarginalizeOldestKeyframe)->Unit(benchmark::kMicrosecond);

}  // namespace
