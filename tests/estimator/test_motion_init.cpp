// Visual-inertial initialization in motion (motion_init.hpp): the closed form recovers gravity and velocity from
// two seconds of a simulated flight that never rests, rejects data that do not determine them, and the sliding
// window started from it follows the flight.
#include <gtest/gtest.h>

#include <cmath>

#include "sliding_window_sim.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/motion_init.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/eval/evaluate.hpp"

namespace twinslam::estimator {
namespace {

using testing::SimRun;
constexpr double kDeg = 180.0 / M_PI;

std::vector<MotionInitFrame> init_frames(const SimRun& run, double t0_s, double t1_s) {
  std::vector<MotionInitFrame> out;
  for (const auto& f : run.frames) {
    if (f.stamp_ns < t0_s * 1e9 || f.stamp_ns > t1_s * 1e9) continue;
    MotionInitFrame m;
    m.stamp_ns = f.stamp_ns;
    for (const auto& b : f.features) m.bearings[b.id] = b.f_C;
    out.push_back(std::move(m));
  }
  return out;
}

const testing::SimFrame& frame_at(const SimRun& run, std::int64_t stamp_ns) {
  for (const auto& f : run.frames) if (f.stamp_ns == stamp_ns) return f;
  throw std::runtime_error("no frame");
}

// Gravity in the oldest body frame within 1.5 deg, and the newest frame's velocity (compared in its body axes, which
// do not depend on L's yaw) and tilt within 0.15 m/s and 1.5 deg, on several seeds and start times, biased noisy IMU and
// 0.5 px features.
TEST(MotionInit, RecoversGravityAndVelocityFromTwoSecondsOfFlight) {
  const SimRun run = testing::make_sim_run(8.0, 0.5, 21);
  const Eigen::Isometry3d T_BC = run.T_BC;
  for (double t0 : {0.2, 1.5, 3.0, 5.5}) {
    const auto frames = init_frames(run, t0, t0 + 2.0);
    MotionInitConfig c;
    c.pixel_sigma = 0.5;
    const auto r = try_motion_init(frames, run.imu, T_BC, ImuNoise{}, 9.81, 460.0, c);
    ASSERT_TRUE(r.has_value()) << "t0 " << t0;
    const auto& first = frame_at(run, frames.front().stamp_ns).truth;
    const auto& last = frame_at(run, frames.back().stamp_ns).truth;
    const Eigen::Vector3d g_B0 = first.q_LB.inverse() * Eigen::Vector3d(0, 0, -9.81);
    const double g_err_deg = std::acos(std::clamp(g_B0.normalized().dot(r->g_B0.normalized()), -1.0, 1.0)) * kDeg;
    const Eigen::Vector3d v_B_true = last.q_LB.inverse() * last.v_L;
    const Eigen::Vector3d v_B_est = r->state.q_LB.inverse() * r->state.v_L;
    const Eigen::Vector3d up_true = last.q_LB.inverse() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up_est = r->state.q_LB.inverse() * Eigen::Vector3d::UnitZ();
    const double tilt_err_deg = std::acos(std::clamp(up_true.dot(up_est), -1.0, 1.0)) * kDeg;
    std::printf("t0 %.1f s: gravity %.3f deg, tilt %.3f deg, velocity %.3f m/s of %.2f, %d landmarks, "
                "sigma tilt %.3f deg v %.3f m/s, median %.2f px, excitation %.2f m/s^2\n", t0, g_err_deg, tilt_err_deg,
                (v_B_est - v_B_true).norm(), v_B_true.norm(), r->landmarks, r->tilt_sigma_deg, r->velocity_sigma_mps,
                r->median_error_px, r->excitation_mps2);
    // The accelerometer bias (0.05 m/s^2 per axis here) is barely separable from gravity in 2 s: about 0.5 deg.
    EXPECT_LT(g_err_deg, 1.5);
    EXPECT_LT(tilt_err_deg, 1.5);
    EXPECT_LT((v_B_est - v_B_true).norm(), 0.15);
    const Eigen::Matrix3d R_LB = r->state.q_LB.toRotationMatrix();
    EXPECT_NEAR(std::atan2(R_LB(1, 0), R_LB(0, 0)), 0.0, 1e-9);  // L's heading is the newest body's
    EXPECT_TRUE(r->state.p_L.isZero());
  }
}

TEST(MotionInit, RejectsTooLittleDataAndBadConfig) {
  const SimRun run = testing::make_sim_run(3.0, 0.5, 22);
  const MotionInitConfig c;
  // Shorter than min_span_s.
  EXPECT_FALSE(try_motion_init(init_frames(run, 0.2, 0.2 + 0.5 * c.min_span_s), run.imu, run.T_BC, ImuNoise{}, 9.81,
                               460.0, c));
  // Too few landmarks.
  auto frames = init_frames(run, 0.2, 2.2);
  for (auto& f : frames) std::erase_if(f.bearings, [](const auto& kv) { return kv.first >= 10; });
  EXPECT_FALSE(try_motion_init(frames, run.imu, run.T_BC, ImuNoise{}, 9.81, 460.0, c));
  // IMU that does not cover the frames.
  const std::vector<ImuSample> late(run.imu.begin() + 100, run.imu.end());
  EXPECT_FALSE(try_motion_init(init_frames(run, 0.2, 2.2), late, run.T_BC, ImuNoise{}, 9.81, 460.0, c));
  MotionInitConfig bad;
  bad.min_span_s = bad.window_s + 1.0;
  EXPECT_THROW(bad.validate(), InputError);
  MotionInitConfig negative;
  negative.min_excitation_mps2 = -0.1;
  EXPECT_THROW(negative.validate(), InputError);
}

// Steady flight (constant velocity, no turn) does not determine the metric scale: the camera centres c_k = v_0 t_k
// fit every ray for any speed, landmarks scaled with it. The closed form must refuse rather than return one of those
// solutions (issue 14: an estimator restarted in flight at 3 m/s started from 0.06-0.1 m/s, with a velocity sigma of
// 0.01-0.02 m/s that passed the absolute test, because at a collapsed scale every landmark is close and every sigma
// shrinks with it). The gravity-free acceleration measured here is ~0.01 m/s^2 (flights above: ~1 m/s^2).
testing::AnalyticTrajectory steady_flight(double speed_mps) {
  testing::AnalyticTrajectory steady;
  steady.position = {testing::Sinusoid{0.0, speed_mps, 0.0}, testing::Sinusoid{1.0, 0.0, 0.0},
                     testing::Sinusoid{5.0, 0.0, 0.0}};
  steady.yaw = steady.pitch = steady.roll = testing::Sinusoid{};
  return steady;
}

TEST(MotionInit, RefusesSteadyFlightWhereTheScaleIsUndetermined) {
  for (unsigned seed : {31u, 32u, 33u}) {
    const SimRun run = testing::make_sim_run(8.0, 0.5, seed, 2000, 460.0, steady_flight(3.0), {30.0, 50.0, 60.0});
    for (double t0 : {0.5, 2.5, 5.0}) {
      MotionInitConfig c;
      c.pixel_sigma = 0.5;
      const auto r = try_motion_init(init_frames(run, t0, t0 + 2.0), run.imu, run.T_BC, ImuNoise{}, 9.81, 460.0, c);
      EXPECT_FALSE(r.has_value()) << "seed " << seed << " t0 " << t0 << ": speed " << r->state.v_L.norm()
                                  << " m/s (truth 3), excitation " << r->excitation_mps2 << " m/s^2";
    }
  }
}

// Steady flight is neither rest nor a motion the closed form can scale (issue 14: an estimator restarted in flight took
// 3 m/s for 0 and diverged). At a constant 3 m/s with facades 30-60 m away consecutive frames move the features about
// 1 px and the IMU feels only gravity, which passed the old frame-to-frame stillness test; over the static window they
// move several pixels. The estimator waits (no pose) rather than start from a wrong speed.
TEST(SlidingWindow, SteadyFlightIsNeitherRestNorAScaledMotion) {
  const SimRun run = testing::make_sim_run(8.0, 0.5, 31u, 2000, 460.0, steady_flight(3.0), {30.0, 50.0, 60.0});
  SlidingWindowConfig c;
  c.T_BC = run.T_BC;
  c.pixel_sigma = 0.5;
  SlidingWindowEstimator est(c);
  std::size_t imu_next = 0, tracking = 0;
  for (const auto& f : run.frames) {
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) est.add_imu(run.imu[imu_next++]);
    const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
    if (e.status != EstimatorStatus::kTracking) continue;
    ++tracking;
    EXPECT_NEAR(e.v_L.norm(), 3.0, 1.0) << "at " << 1e-9 * static_cast<double>(f.stamp_ns) << " s";
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_EQ(tracking, 0u) << "initialized in steady flight";
}

// The estimator, never at rest and never told the state, initializes within 3 s of its first frame and then follows
// the flight: ATE after posyaw alignment (L is gravity-aligned with its own yaw and origin) below 0.3 m over ~10 s
// (15 m), ATE_R below 2 deg, on three seeds.
TEST(SlidingWindow, InitializesInMotionAndFollowsTheFlight) {
  for (unsigned seed : {23u, 24u, 25u}) {
    const SimRun run = testing::make_sim_run(12.0, 0.5, seed);
    SlidingWindowConfig c;
    c.T_BC = run.T_BC;
    c.pixel_sigma = 0.5;
    c.max_solver_time_s = 10.0;
    SlidingWindowEstimator est(c);
    std::size_t imu_next = 0;
    Trajectory truth, estimate;
    std::int64_t init_ns = -1;
    for (const auto& f : run.frames) {
      while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) est.add_imu(run.imu[imu_next++]);
      const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
      if (e.status != EstimatorStatus::kTracking) {
        EXPECT_LT(init_ns, 0) << "lost tracking at " << f.stamp_ns;
        continue;
      }
      if (init_ns < 0) init_ns = f.stamp_ns;
      estimate.poses.push_back({f.stamp_ns, e.T_LB});
      truth.poses.push_back({f.stamp_ns, geometry::make_pose(f.truth.q_LB, f.truth.p_L)});
    }
    ASSERT_GE(init_ns, 0) << "never initialized";
    eval::EvalConfig ec;
    ec.align = eval::AlignMode::PosYaw;
    const eval::EvalResult r = eval::evaluate(truth, estimate, ec);
    std::printf("seed %u: initialized %.2f s after the first frame; ATE_p %.3f m (max %.3f) over %.1f m, ATE_R %.2f deg\n",
                seed, 1e-9 * static_cast<double>(init_ns - run.frames.front().stamp_ns), r.ate.pos.rmse, r.ate.pos.max,
                r.length_m, r.ate.rot.rmse);
    EXPECT_LE(init_ns - run.frames.front().stamp_ns, 3'000'000'000);
    EXPECT_LT(r.ate.pos.rmse, 0.3);  // measured 0.08-0.20 m; a wrong scale or gravity gives metres
    EXPECT_LT(r.ate.rot.rmse, 2.0);  // the bound of the tiny-scenario test (test_sliding_window_dataset)
  }
}

}  // namespace
}  // namespace twinslam::estimator
