#pragma once
// Pictures of the frontend's tracks for READMEs and debugging: each feature as a dot with a tail through its last
// positions, coloured from red (new) to green (tracked for 20 frames or more).
#include <cstdint>
#include <deque>
#include <unordered_map>

#include <opencv2/core.hpp>

#include "twinslam/tracking/frontend.hpp"

namespace twinslam::tracking {

class TrackHistory {
 public:
  explicit TrackHistory(std::size_t max_positions = 10) : max_positions_(max_positions) {}

  // Appends each feature's pixel to its tail; features absent from `frame` are forgotten.
  void add(const FrameResult& frame);

  // BGR picture of `mono8` (the frame last added) with every feature's tail and dot.
  cv::Mat draw(const cv::Mat& mono8, const FrameResult& frame) const;

 private:
  std::size_t max_positions_;
  std::unordered_map<std::uint64_t, std::deque<cv::Point2f>> tails_;
};

}  // namespace twinslam::tracking
