// The sliding-window estimator on simulated flights: accuracy against ground truth, bounded window, outlier tracks.
// Its online calibration (camera mounting, lens): test_sliding_window_calibration.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "sliding_window_run.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"

namespace twinslam::estimator {
namespace {

using testing::RunResult;
using testing::run_estimator;
using testing::sim_config;
using testing::SimRun;

TEST(SlidingWindow, FollowsSimulatedFlightWithinBound) {
  const SimRun run = testing::make_sim_run(20.0, 0.5, 11);
  SlidingWindowEstimator est(sim_config(run, 0.5));
  const RunResult r = run_estimator(est, run);
  std::vector<double> ms = r.estimator_ms;
  std::sort(ms.begin(), ms.end());
  // Informational (no timing asserts in tests): the benchmark is the place for speed.
  std::printf("rmse %.3f m, max %.3f m, max rot %.2f deg, max v err %.3f m/s, keyframes %d, estimator ms median %.1f "
              "p99 %.1f\n", r.rmse_position_m, r.max_position_m, r.max_rotation_deg, r.max_speed_error_mps, r.keyframes,
              ms[ms.size() / 2], ms[ms.size() * 99 / 100]);
  EXPECT_EQ(r.not_tracking, 0);
  // About 30 m of flight: position error (ATE RMSE, no alignment: L is initialized from the true state) < 0.1 m
  // (measured 0.03 m).
  EXPECT_LT(r.rmse_position_m, 0.1);
  EXPECT_LT(r.max_rotation_deg, 2.0);
  EXPECT_LT(r.max_speed_error_mps, 0.2);
}

TEST(SlidingWindow, MarginalizationKeepsWindowBounded) {
  const SimRun run = testing::make_sim_run(12.0, 0.5, 12);
  SlidingWindowConfig c = sim_config(run, 0.5);
  c.window_keyframes = 5;
  SlidingWindowEstimator est(c);
  const RunResult r = run_estimator(est, run);
  EXPECT_GT(r.keyframes, 3 * c.window_keyframes);       // the window slid several times
  EXPECT_LE(r.max_keyframes, static_cast<std::size_t>(c.window_keyframes));
  EXPECT_LE(r.max_landmarks, static_cast<std::size_t>(c.max_landmarks));
  EXPECT_LT(r.rmse_position_m, 0.3);
}

TEST(SlidingWindow, OutlierTrackIsRemovedAndAccuracyKept) {
  const SimRun run = testing::make_sim_run(15.0, 0.5, 13);
  SlidingWindowEstimator est(sim_config(run, 0.5));
  // Ten tracks whose bearings jump between unrelated directions (mismatches of a front end), in every frame; they
  // must never pass triangulation.
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  // And twenty tracks that copy a true track (so they are triangulated as good landmarks) until frame 100, then slip
  // by 2 deg (about 16 px) and stay there (a tracker that jumped to a neighbouring corner): after the slip their
  // observations must be removed as outliers, or they would bend the window.
  const auto& first = run.frames.front().features;
  const auto slip = Eigen::AngleAxisd(2.0 * 3.14159265358979 / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const RunResult r = run_estimator(est, run, [&](std::size_t frame, std::vector<FeatureBearing>& f) {
    for (int k = 0; k < 10; ++k) {
      f.push_back({1'000'000 + k, Eigen::Vector3d(0.3 * n(rng), 0.3 * n(rng), 1.0).normalized()});
    }
    const std::size_t n_true = f.size() - 10;
    for (int k = 0; k < 20 && k < static_cast<int>(first.size()); ++k) {
      for (std::size_t i = 0; i < n_true; ++i) {
        if (f[i].id != first[k].id) continue;
        f.push_back({2'000'000 + k, frame < 100 ? f[i].f_C : Eigen::Vector3d(slip * f[i].f_C)});
      }
    }
  });
  EXPECT_EQ(r.not_tracking, 0);
  EXPECT_LT(r.rmse_position_m, 0.1);
  for (const auto& map : r.maps) {
    for (const auto& lm : map.landmarks) {
      EXPECT_TRUE(lm.id < 1'000'000 || lm.id >= 2'000'000) << "random outlier track in the local map";
    }
  }
}

TEST(SlidingWindow, LocalMapLandmarksAreNearTheTruePoints) {
  const SimRun run = testing::make_sim_run(8.0, 0.5, 14);
  SlidingWindowEstimator est(sim_config(run, 0.5));
  const RunResult r = run_estimator(est, run);
  ASSERT_FALSE(r.maps.empty());
  const auto& last = r.maps.back();
  ASSERT_GT(last.landmarks.size(), 20u);
  std::vector<double> errors;
  for (const auto& lm : last.landmarks) {
    EXPECT_GE(lm.quality, 0.0);
    EXPECT_LE(lm.quality, 1.0);
    errors.push_back((lm.p_L - run.points.at(static_cast<std::size_t>(lm.id))).norm());
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  // Points 15-40 m away, 0.5 px noise, a few metres of baseline: the median error is well below a metre.
  EXPECT_LT(errors[errors.size() / 2], 1.0);
}

TEST(SlidingWindow, ReportsInitializingWithoutRestAndRejectsBadInput) {
  const SimRun run = testing::make_sim_run(7.0, 0.5, 15);
  SlidingWindowConfig c = sim_config(run, 0.5);
  c.motion_init.enabled = false;  // only rest may start it here: the timeout report is what is tested
  SlidingWindowEstimator est(c);
  std::size_t imu_next = 0;
  FrameEstimate last;
  for (const auto& f : run.frames) {
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) est.add_imu(run.imu[imu_next++]);
    last = est.add_frame(f.stamp_ns, f.features);
    EXPECT_EQ(last.status, EstimatorStatus::kInitializing);  // the analytic flight never rests
  }
  EXPECT_TRUE(last.init_timed_out);
  EXPECT_THROW(est.add_frame(run.frames.back().stamp_ns, {}), InputError);
  EXPECT_THROW(est.add_imu(run.imu.front()), InputError);
  // Finite but beyond any IMU's range (a corrupt sample): refused before it can overflow the state.
  ImuSample wild = run.imu.back();
  wild.stamp_ns += 1'000'000;
  wild.accel_B.x() = 1e100;
  try {
    est.add_imu(wild);
    ADD_FAILURE() << "accepted an acceleration of 1e100 m/s^2";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond any IMU's range"), std::string::npos) << e.what();
  }
  c.window_keyframes = 1;
  EXPECT_THROW(SlidingWindowEstimator{c}, InputError);
}

}  // namespace
}  // namespace twinslam::estimator

namespace twinslam::estimator {
namespace {

// Divergence plumbing: a speed limit below the flight's speed (about 1-2 m/s) is "divergence"; the estimator resets,
// reports kReinitializing until it is initialized again, then tracks again from the new start.
TEST(SlidingWindow, DivergenceResetsAndReportsReinitializing) {
  const SimRun run = testing::make_sim_run(6.0, 0.5, 16);
  SlidingWindowConfig c = sim_config(run, 0.5);
  c.max_speed_mps = 0.2;
  SlidingWindowEstimator est(c);
  std::size_t imu_next = 0;
  est.initialize_next_frame(run.frames.front().truth);
  std::vector<EstimatorStatus> status;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    const auto& f = run.frames[k];
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) est.add_imu(run.imu[imu_next++]);
    if (k == 60) est.initialize_next_frame(f.truth);
    status.push_back(est.add_frame(f.stamp_ns, f.features).status);
  }
  EXPECT_EQ(status[0], EstimatorStatus::kTracking);           // the start itself has no solve yet
  EXPECT_EQ(status[1], EstimatorStatus::kReinitializing);     // the first solve sees |v| > 0.2 m/s
  EXPECT_EQ(status[30], EstimatorStatus::kReinitializing);    // stays so: the flight never rests
  EXPECT_EQ(status[60], EstimatorStatus::kTracking);          // initialized again
  EXPECT_EQ(est.keyframe_count(), 0u);                         // ...and reset again by the next solve
}

}  // namespace
}  // namespace twinslam::estimator

#include "position_provider.hpp"

namespace twinslam::estimator {
namespace {

Eigen::Vector3d f_last_truth(const SimRun& run) { return run.frames.back().truth.p_L; }

TEST(SlidingWindow, ExtraFactorProvidersJoinTheProblem) {
  const SimRun run = testing::make_sim_run(3.0, 0.5, 17);
  SlidingWindowEstimator est(sim_config(run, 0.5));
  auto provider = std::make_shared<testing::PositionProvider>();
  est.add_factor_provider(provider);
  est.initialize_next_frame(run.frames.front().truth);
  std::size_t imu_next = 0;
  FrameEstimate last;
  for (const auto& f : run.frames) {
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) est.add_imu(run.imu[imu_next++]);
    // A GNSS-like fix of every frame at its true position (1 cm sigma); W = L here (T_WL starts at the identity).
    provider->add_fix(f.stamp_ns, f.truth.p_L, 0.01);
    last = est.add_frame(f.stamp_ns, f.features);
  }
  // Every solve builds the term list once, and every marginalization once more.
  EXPECT_GE(provider->calls, run.frames.size() - 1);
  EXPECT_GT(provider->terms_added, 0u);
  EXPECT_TRUE(last.aligned);
  EXPECT_LT(((last.T_WL * last.T_LB).translation() - f_last_truth(run)).norm(), 0.03);
}

}  // namespace
}  // namespace twinslam::estimator

namespace twinslam::estimator {
namespace {

// At rest (as the EuRoC excerpt): static initialization from the IMU once the features stand still, gravity direction
// within 1 deg, and the zero-velocity factors keep the position from drifting with the unknown accelerometer bias.
// Also with a gyro bias as large as EuRoC's ADIS16448 (0.08 rad/s): over the static window it would turn the
// features 11 px if the rest test did not fit the bias (visual_rest.cpp).
TEST(SlidingWindow, StaticStartInitializesAndHoldsStill) {
  testing::AnalyticTrajectory rest;
  for (auto& axis : rest.position) axis = testing::Sinusoid{axis.c, 0.0, 0.0, 1.0, 0.0};
  rest.yaw = testing::Sinusoid{0.3, 0.0, 0.0, 1.0, 0.0};
  rest.pitch = testing::Sinusoid{-0.05, 0.0, 0.0, 1.0, 0.0};
  rest.roll = testing::Sinusoid{0.1, 0.0, 0.0, 1.0, 0.0};
  // 0.1 px: a KLT tracker on a still image jitters far less than the simulator's default 0.5 px.
  SimRun run = testing::make_sim_run(6.0, 0.1, 18, 2000, 460.0, rest);
  for (const Eigen::Vector3d& extra_gyro_bias : {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(-0.002, 0.021, 0.077)}) {
    for (auto& x : run.imu) x.gyro_B += extra_gyro_bias;
    SlidingWindowEstimator est(sim_config(run, 0.1));
    std::size_t imu_next = 0;
    std::optional<Eigen::Vector3d> p0;
    double max_drift = 0.0, max_tilt_deg = 0.0;
    for (const auto& f : run.frames) {
      while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) est.add_imu(run.imu[imu_next++]);
      const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
      if (e.status != EstimatorStatus::kTracking) {
        EXPECT_FALSE(p0.has_value()) << "lost tracking at rest";
        continue;
      }
      if (!p0) p0 = e.T_LB.translation();
      max_drift = std::max(max_drift, (e.T_LB.translation() - *p0).norm());
      // Gravity direction in B: estimated R_LB^T e_z against the true R_WB^T e_z (yaw-free).
      const Eigen::Vector3d up_est = e.T_LB.linear().transpose().col(2), up_true = f.truth.q_LB.toRotationMatrix().row(2);
      max_tilt_deg = std::max(max_tilt_deg, std::acos(std::clamp(up_est.dot(up_true), -1.0, 1.0)) * 180.0 / M_PI);
    }
    ASSERT_TRUE(p0.has_value()) << "never initialized with an extra gyro bias of " << extra_gyro_bias.norm() << " rad/s";
    std::printf("rest, extra gyro bias %.3f rad/s: drift %.4f m, tilt error %.2f deg\n", extra_gyro_bias.norm(),
                max_drift, max_tilt_deg);
    EXPECT_LT(max_tilt_deg, 1.0);
    EXPECT_LT(max_drift, 0.03);
  }
}

}  // namespace
}  // namespace twinslam::estimator
