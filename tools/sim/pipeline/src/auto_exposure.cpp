#include "twinslam/sim/auto_exposure.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"

namespace twinslam::sim {

AutoExposureConfig auto_exposure_config(const Scenario& scenario) {
  AutoExposureConfig c;
  c.tau_s = scenario.camera.auto_exposure_tau_s;
  c.frame_period_s = 1.0 / scenario.camera.rate_hz;
  return c;
}

AutoExposure::AutoExposure(const AutoExposureConfig& config) : config_(config) {
  if (!(config_.tau_s >= 0) || !(config_.frame_period_s > 0) ||
      !(config_.target_mean > 0 && config_.target_mean < 255) ||
      !(config_.min_gain > 0 && config_.min_gain <= 1 && config_.max_gain >= 1))
    throw InputError(
        "auto-exposure: tau_s >= 0, frame_period_s > 0, target_mean in (0, 255), min_gain <= 1 <= max_gain");
}

cv::Mat AutoExposure::apply(const cv::Mat& rendered) {
  if (config_.tau_s == 0) return rendered;
  CV_Assert(rendered.type() == CV_8UC1);
  auto clamp = [&](double g) { return std::clamp(g, config_.min_gain, config_.max_gain); };
  const double floor_mean = 1.0;  // a black frame must not drive log(mean) to -inf
  if (!started_) {
    gain_ = clamp(config_.target_mean / std::max(cv::mean(rendered)[0], floor_mean));
    started_ = true;
  }
  cv::Mat out;
  rendered.convertTo(out, CV_8U, gain_);  // rounds and saturates at 0 and 255
  delivered_gain_ = gain_;
  const double alpha = 1.0 - std::exp(-config_.frame_period_s / config_.tau_s);
  const double error = std::log(config_.target_mean) - std::log(std::max(cv::mean(out)[0], floor_mean));
  gain_ = clamp(std::exp(std::log(gain_) + alpha * error));
  return out;
}

}  // namespace twinslam::sim
