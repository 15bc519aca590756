#include "detector.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace twinslam::tracking {
namespace {

struct Corner {
  float score;
  cv::Point2f px;
};

// Local maxima (3x3) of the min-eigenvalue map of one bucket above max(quality * best, floor), strongest first.
std::vector<Corner> bucket_corners(const cv::Mat& image, const cv::Rect& roi, const FrontendConfig& config) {
  cv::Mat1f eig, dilated;
  // On an ROI header OpenCV's filters read the real neighbouring pixels, so bucket edges get no artificial corners.
  cv::cornerMinEigenVal(image(roi), eig, 3, 3);
  cv::dilate(eig, dilated, cv::Mat());
  double best = 0.0;
  cv::minMaxLoc(eig, nullptr, &best);
  const float threshold = static_cast<float>(std::max(config.quality_level * best, config.min_eigenvalue));
  std::vector<Corner> corners;
  for (int y = 0; y < eig.rows; ++y) {
    const float* e = eig[y];
    const float* d = dilated[y];
    for (int x = 0; x < eig.cols; ++x) {
      if (e[x] >= threshold && e[x] >= d[x]) {
        corners.push_back({e[x], cv::Point2f(static_cast<float>(roi.x + x), static_cast<float>(roi.y + y))});
      }
    }
  }
  std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.score > b.score; });
  return corners;
}

}  // namespace

void mark_taken(cv::Mat1b& taken, const cv::Point2f& px, double min_distance_px) {
  const int r = static_cast<int>(std::ceil(min_distance_px));
  if (r <= 0) {
    if (is_free(taken, px)) taken(cvRound(px.y), cvRound(px.x)) = 255;
    return;
  }
  cv::circle(taken, cv::Point(cvRound(px.x), cvRound(px.y)), r, cv::Scalar(255), cv::FILLED);
}

std::vector<cv::Point2f> detect_bucketed(const cv::Mat& image, const std::vector<cv::Point2f>& existing,
                                         cv::Mat1b& taken, int wanted, const FrontendConfig& config,
                                         std::vector<int>* barren) {
  std::vector<cv::Point2f> added;
  if (wanted <= 0) return added;
  const int cols = config.grid_cols, rows = config.grid_rows;
  const cv::Rect inner(config.border_px, config.border_px, image.cols - 2 * config.border_px,
                       image.rows - 2 * config.border_px);
  if (inner.width <= 0 || inner.height <= 0) return added;
  const int share = (config.max_features + cols * rows - 1) / (cols * rows);
  barren->resize(cols * rows, 0);

  std::vector<int> count(cols * rows, 0);
  auto bucket_of = [&](const cv::Point2f& p) {
    const int c = std::clamp(static_cast<int>((p.x - inner.x) * cols / inner.width), 0, cols - 1);
    const int r = std::clamp(static_cast<int>((p.y - inner.y) * rows / inner.height), 0, rows - 1);
    return r * cols + c;
  };
  for (const auto& p : existing) ++count[bucket_of(p)];

  // Pass 1: fill each bucket to its share, so texture-rich areas cannot take every feature. Emptiest buckets first,
  // in case `wanted` runs out before every bucket had its turn.
  std::vector<int> order(cols * rows);
  for (int b = 0; b < cols * rows; ++b) order[b] = b;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return count[a] < count[b]; });
  std::vector<Corner> leftover;
  for (int b : order) {
    if (static_cast<int>(added.size()) >= wanted) break;
    if (count[b] >= share) continue;
    if ((*barren)[b] > 0) {
      --(*barren)[b];
      continue;
    }
    const int c = b % cols, r = b / cols;
    const int x0 = inner.x + c * inner.width / cols, x1 = inner.x + (c + 1) * inner.width / cols;
    const int y0 = inner.y + r * inner.height / rows, y1 = inner.y + (r + 1) * inner.height / rows;
    const std::vector<Corner> corners = bucket_corners(image, cv::Rect(x0, y0, x1 - x0, y1 - y0), config);
    if (corners.empty()) (*barren)[b] = kBarrenSkips;
    for (const Corner& corner : corners) {
      if (count[b] < share && static_cast<int>(added.size()) < wanted) {
        if (!is_free(taken, corner.px)) continue;
        added.push_back(corner.px);
        mark_taken(taken, corner.px, config.min_distance_px);
        ++count[b];
      } else {
        leftover.push_back(corner);
      }
    }
  }
  // Pass 2: buckets without texture leave a deficit; the strongest remaining corners anywhere make it up.
  std::sort(leftover.begin(), leftover.end(), [](const Corner& a, const Corner& b) { return a.score > b.score; });
  for (const Corner& corner : leftover) {
    if (static_cast<int>(added.size()) >= wanted) break;
    if (!is_free(taken, corner.px)) continue;
    added.push_back(corner.px);
    mark_taken(taken, corner.px, config.min_distance_px);
  }
  return added;
}

}  // namespace twinslam::tracking
