#pragma once
// The sliding-window estimator run over a simulated flight (sliding_window_sim.hpp) and scored against its truth: the
// shared driver of the window's accuracy and calibration tests.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "sliding_window_sim.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"

namespace twinslam::testing {

using estimator::EstimatorStatus;
using estimator::FeatureBearing;
using estimator::FrameEstimate;
using estimator::ImuBias;
using estimator::ImuState;
using estimator::LocalMapEstimate;
using estimator::SlidingWindowConfig;
using estimator::SlidingWindowEstimator;

struct RunResult {
  double rmse_position_m = 0.0;    // over frames after the first 2 s
  double max_position_m = 0.0;
  double max_rotation_deg = 0.0;
  double max_speed_error_mps = 0.0;
  std::size_t max_keyframes = 0;
  std::size_t max_landmarks = 0;
  int keyframes = 0;
  int not_tracking = 0;
  std::vector<double> estimator_ms;
  std::vector<LocalMapEstimate> maps;
};

inline SlidingWindowConfig sim_config(const SimRun& run, double pixel_sigma) {
  SlidingWindowConfig c;
  c.T_BC = run.T_BC;
  c.pixel_sigma = pixel_sigma;
  c.max_solver_time_s = 10.0;  // deterministic: only the iteration count bounds the solver in tests
  return c;
}

// Feeds IMU up to each frame's stamp, then the frame. The window starts from the true state of the first frame
// (L = W of the simulation) with zero bias, so the estimate is compared to the truth without alignment.
inline RunResult run_estimator(SlidingWindowEstimator& est, const SimRun& run,
                        const std::function<void(std::size_t, std::vector<FeatureBearing>&)>& edit = {}) {
  RunResult r;
  std::size_t imu_next = 0;
  ImuState init = run.frames.front().truth;
  init.bias = ImuBias{};
  est.initialize_next_frame(init);
  double sum_sq = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    const auto& f = run.frames[k];
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns + 5'000'000) est.add_imu(run.imu[imu_next++]);
    std::vector<FeatureBearing> features = f.features;
    if (edit) edit(k, features);
    const FrameEstimate e = est.add_frame(f.stamp_ns, features);
    if (e.status != EstimatorStatus::kTracking) {
      ++r.not_tracking;
      continue;
    }
    r.keyframes += e.keyframe ? 1 : 0;
    r.estimator_ms.push_back(e.estimator_ms);
    r.max_keyframes = std::max(r.max_keyframes, est.keyframe_count());
    r.max_landmarks = std::max(r.max_landmarks, est.landmark_count());
    if (est.local_map()) r.maps.push_back(*est.local_map());
    if (f.stamp_ns < 2'000'000'000) continue;
    const double dp = (e.T_LB.translation() - f.truth.p_L).norm();
    const double dR = Eigen::AngleAxisd(Eigen::Quaterniond(e.T_LB.linear()).inverse() * f.truth.q_LB).angle();
    sum_sq += dp * dp;
    ++n;
    r.max_position_m = std::max(r.max_position_m, dp);
    r.max_rotation_deg = std::max(r.max_rotation_deg, dR * 180.0 / 3.14159265358979);
    r.max_speed_error_mps = std::max(r.max_speed_error_mps, (e.v_L - f.truth.v_L).norm());
  }
  r.rmse_position_m = n > 0 ? std::sqrt(sum_sq / n) : 1e9;
  return r;
}

}  // namespace twinslam::testing
