#include "twinslam/tracking/track_drawing.hpp"

#include <algorithm>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace twinslam::tracking {

void TrackHistory::add(const FrameResult& frame) {
  std::unordered_map<std::uint64_t, std::deque<cv::Point2f>> next;
  for (const TrackedFeature& f : frame.features) {
    auto tail = std::move(tails_[f.id]);
    tail.emplace_back(static_cast<float>(f.uv.x()), static_cast<float>(f.uv.y()));
    while (tail.size() > max_positions_) tail.pop_front();
    next.emplace(f.id, std::move(tail));
  }
  tails_ = std::move(next);
}

cv::Mat TrackHistory::draw(const cv::Mat& mono8, const FrameResult& frame) const {
  cv::Mat bgr;
  cv::cvtColor(mono8, bgr, cv::COLOR_GRAY2BGR);
  constexpr int kShift = 4;  // sub-pixel drawing: coordinates in 1/16 px
  auto fixed = [](const cv::Point2f& p) { return cv::Point(cvRound(p.x * 16.f), cvRound(p.y * 16.f)); };
  for (const TrackedFeature& f : frame.features) {
    const double a = std::min(1.0, (f.track_length - 1) / 19.0);  // 0 = new, 1 = 20 frames or more
    const cv::Scalar colour(0, 255 * a, 255 * (1.0 - a));             // BGR: red -> green
    const auto it = tails_.find(f.id);
    if (it != tails_.end() && it->second.size() > 1) {
      std::vector<cv::Point> line;
      for (const auto& p : it->second) line.push_back(fixed(p));
      cv::polylines(bgr, line, false, colour, 1, cv::LINE_AA, kShift);
    }
    cv::circle(bgr, fixed(cv::Point2f(static_cast<float>(f.uv.x()), static_cast<float>(f.uv.y()))), 2 * 16, colour,
               cv::FILLED, cv::LINE_AA, kShift);
  }
  return bgr;
}

}  // namespace twinslam::tracking
