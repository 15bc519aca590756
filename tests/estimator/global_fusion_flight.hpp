// The flight the GlobalFusion tests share (test_global_fusion.cpp, test_world_declaration.cpp): a 30 s
// figure-eight in a landmark shell, the window they fly it through, and the IMU feed before each frame.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "sliding_window_sim.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"

namespace twinslam::testing {

// 30 s of a figure-eight (50 x 25 m) inside a landmark shell, as in test_world_alignment.
inline SimRun flight() {
  AnalyticTrajectory traj;
  const double w = 2.0 * M_PI / 60.0;
  traj.position[0] = {0.0, 0.0, 25.0, w, 0.0};
  traj.position[1] = {0.0, 0.0, 12.5, 2.0 * w, 0.0};
  return make_sim_run(30.0, 0.5, 5, 8000, 460.0, traj, {30.0, 45.0, 45.0});
}

// The window every flight here uses: the run's extrinsics, 0.5 px, a time cap that never binds (deterministic).
inline estimator::SlidingWindowConfig window_config(const SimRun& run) {
  estimator::SlidingWindowConfig c;
  c.T_BC = run.T_BC;
  c.pixel_sigma = 0.5;
  c.max_solver_time_s = 10.0;
  return c;
}

// The IMU samples up to 5 ms past a frame, before that frame.
inline void feed_imu(const SimRun& run, estimator::SlidingWindowEstimator& est, std::size_t& next,
                     std::int64_t stamp_ns) {
  while (next < run.imu.size() && run.imu[next].stamp_ns <= stamp_ns + 5'000'000) est.add_imu(run.imu[next++]);
}

}  // namespace twinslam::testing
