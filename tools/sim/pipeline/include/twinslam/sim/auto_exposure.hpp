#pragma once
// Auto-exposure of the simulated camera (camera.auto_exposure_tau_s): a post-process on each rendered 8-bit frame, as
// the gain of a real camera's exposure loop. The renderer's image is the scene at gain 1; the camera delivers
//   out_k = clip(round(g_k * rendered_k), 0, 255)
// and meters what it delivered for the next frame (a real loop cannot see a frame before exposing it):
//   log g_{k+1} = log g_k + alpha (log target - log mean(out_k)),   alpha = 1 - exp(-frame_period / tau),
// i.e. without clipping a first-order lag of time constant tau toward g* = target / mean(rendered). After a step in
// the scene's brightness the frame's mean jumps with the scene and returns to the target as exp(-t / tau). The first
// frame is exposed at its own g* (the camera settled before the flight), clamped to [min_gain, max_gain].
#include <opencv2/core.hpp>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

struct AutoExposureConfig {
  double tau_s = 0.3;            // time constant of the loop [s]; 0 turns auto-exposure off (gain 1)
  double frame_period_s = 0.05;  // [s]
  double target_mean = 100;      // mean grey level the loop drives a frame to (about 40 % of full scale)
  double min_gain = 0.25;        // exposure x analog gain range around the renderer's nominal exposure
  double max_gain = 4.0;
};

// camera.auto_exposure_tau_s at 1 / camera.rate_hz.
AutoExposureConfig auto_exposure_config(const Scenario& scenario);

class AutoExposure {
 public:
  explicit AutoExposure(const AutoExposureConfig& config);
  // The frame as the camera delivers it (CV_8UC1 in and out). tau_s = 0: `rendered` itself.
  cv::Mat apply(const cv::Mat& rendered);
  // Gain of the last frame delivered (1 before the first and when off).
  double gain() const { return delivered_gain_; }

 private:
  AutoExposureConfig config_;
  double gain_ = 1.0;            // for the next frame
  double delivered_gain_ = 1.0;  // of the last frame
  bool started_ = false;
};

}  // namespace twinslam::sim
