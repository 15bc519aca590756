#pragma once
// Bucketed Shi-Tomasi top-up detection (Shi & Tomasi, "Good Features to Track", CVPR 1994: score = the smaller
// eigenvalue of the 2x2 structure tensor, which is what KLT needs to be well conditioned).
#include <vector>

#include <opencv2/core.hpp>

#include "twinslam/tracking/frontend_config.hpp"

namespace twinslam::tracking {

// Draws a filled disc of radius min_distance_px (0 = free, 255 = taken) around px into `taken`.
void mark_taken(cv::Mat1b& taken, const cv::Point2f& px, double min_distance_px);

// True if px is not inside any disc drawn into `taken`.
inline bool is_free(const cv::Mat1b& taken, const cv::Point2f& px) {
  const int x = cvRound(px.x), y = cvRound(px.y);
  return x >= 0 && y >= 0 && x < taken.cols && y < taken.rows && taken(y, x) == 0;
}

// New corners, at most `wanted`, spread over the config's grid: every bucket is first filled up to its share
// ceil(max_features / buckets) (counting `existing` points in it), then leftover corners of any bucket fill the rest,
// strongest first. Scores are computed only in buckets that lack features. A corner is taken only where `taken` is
// free, and marks its own disc there. Only corners at least config.border_px from the edge are considered.
// barren (grid_cols * grid_rows entries, kept by the caller between frames): a bucket without a single corner above
// the threshold (sky, a white wall) is not scored again for the next kBarrenSkips times it is visited, so textureless
// areas do not cost a full scoring every frame.
inline constexpr int kBarrenSkips = 4;
std::vector<cv::Point2f> detect_bucketed(const cv::Mat& image, const std::vector<cv::Point2f>& existing,
                                         cv::Mat1b& taken, int wanted, const FrontendConfig& config,
                                         std::vector<int>* barren);

}  // namespace twinslam::tracking
