#pragma once
// Camera frames missing from the stream (a dropped frame, a stalled driver: issue 15), told from the stamps alone:
// the estimator sees no sequence numbers of the camera, and a camera's frame period is fixed, so the shortest interval
// seen so far is the period and an interval of more than `factor` periods has frames missing.
#include <cstdint>

namespace twinslam::estimator {

class FrameGapDetector {
 public:
  explicit FrameGapDetector(double factor = 1.8) : factor_(factor) {}
  // True when frames are missing between the previous frame and this one. Stamps that do not increase are ignored.
  bool on_frame(std::int64_t stamp_ns) {
    if (last_ns_ < 0 || stamp_ns <= last_ns_) {
      if (last_ns_ < 0) last_ns_ = stamp_ns;
      return false;
    }
    const std::int64_t dt = stamp_ns - last_ns_;
    last_ns_ = stamp_ns;
    const bool gap = period_ns_ > 0 && static_cast<double>(dt) > factor_ * static_cast<double>(period_ns_);
    if (period_ns_ == 0 || dt < period_ns_) period_ns_ = dt;
    return gap;
  }

 private:
  double factor_;
  std::int64_t last_ns_ = -1;
  std::int64_t period_ns_ = 0;
};

}  // namespace twinslam::estimator
