#pragma once
// Extension point of the sliding window: later factor types (digital-twin map registration, GNSS) add their residuals
// to the window's problem without changes to the estimator. The estimator calls every registered provider each time it
// builds the problem, after its own IMU, visual and prior factors.
#include <cstdint>
#include <vector>

namespace ceres {
class Problem;
}

namespace twinslam::estimator {

// The window's state blocks, oldest first (layouts of imu_state.hpp). The last entry is the newest frame, which may
// be a non-keyframe.
struct WindowBlocks {
  std::vector<std::int64_t> stamps_ns;
  std::vector<double*> pose;        // [p_L, q_LB xyzw], kPoseSize
  std::vector<double*> speed_bias;  // [v_L, b_g, b_a], kSpeedBiasSize
  std::vector<bool> is_keyframe;
};

class WindowFactorProvider {
 public:
  virtual ~WindowFactorProvider() = default;
  // Adds residual blocks on `blocks` to `problem`. The problem does NOT take ownership of cost or loss functions
  // (Problem::Options DO_NOT_TAKE_OWNERSHIP): the provider keeps them alive until the next call or its destruction.
  // Factors added here are not marginalized when a keyframe leaves the window (their information on it is dropped).
  virtual void add_factors(ceres::Problem& problem, const WindowBlocks& blocks) = 0;
};

}  // namespace twinslam::estimator
