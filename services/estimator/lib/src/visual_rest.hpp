#pragma once
// Visual half of the static initialization's rest test (the IMU half is static_init.hpp).
#include <cstdint>
#include <vector>

#include "twinslam/estimator/sliding_window_state.hpp"

namespace twinslam::estimator {

// Records this frame's bearings in s.rest_frames and says whether the features stood still: the mean angle of the
// common tracks to the previous frame's bearings, and to those of every kept frame of the last static_window_s with
// the rotation the gyroscope measured in between removed (its bias fitted, at most max_rest_gyro_bias_radps), are at
// most max_rest_feature_motion_px. Without features the IMU alone decides (true); with none in common (the first
// frame) stillness is not shown (false).
bool visually_still(WindowState& s, std::int64_t stamp_ns, const std::vector<FeatureBearing>& features);

}  // namespace twinslam::estimator
