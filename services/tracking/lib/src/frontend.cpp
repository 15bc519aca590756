#include "twinslam/tracking/frontend.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "detector.hpp"
#include "reference_patch.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/tracking/ransac.hpp"

namespace twinslam::tracking {
namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

[[noreturn]] void bad_input(const std::string& what) { throw InputError(where("tracking::Frontend", 0, what)); }

// KLT leaves a point at the border when its window slides out; such points are not trusted.
constexpr double kKltEdgePx = 1.0;

}  // namespace

Frontend::Frontend(std::shared_ptr<const CameraModel> camera, const FrontendConfig& config)
    : camera_(std::move(camera)), config_(config) {
  if (!camera_) bad_input("no camera model given");
  config_.validate();
  // The presmoothing lowers every corner's minimum eigenvalue (squared gradients), so the absolute floor, which is
  // set for unsmoothed images, is lowered with it: a Gaussian of sigma s scales a gradient at the 3x3 Sobel scale by
  // about 1 / (1 + s^2), the eigenvalue by the square of that.
  detection_config_ = config_;
  const double attenuation = 1.0 / (1.0 + config_.presmooth_sigma_px * config_.presmooth_sigma_px);
  detection_config_.min_eigenvalue *= attenuation * attenuation;
  if (config_.clahe) {
    clahe_ = cv::createCLAHE(config_.clahe_clip_limit, cv::Size(config_.clahe_tiles, config_.clahe_tiles));
  }
}

void Frontend::reset() {
  tracks_.clear();
  barren_.clear();
  prev_pyramid_.clear();
  R_valid_.fill(false);
  has_prev_ = false;
}

FrameResult Frontend::track(std::int64_t stamp_ns, const cv::Mat& mono8, const Eigen::Matrix3d* R_prev_curr_C) {
  const auto t_start = Clock::now();
  if (mono8.empty() || mono8.type() != CV_8UC1) {
    bad_input("image must be mono8 (CV_8UC1), got OpenCV type " + std::to_string(mono8.type()));
  }
  if (mono8.cols != camera_->width() || mono8.rows != camera_->height()) {
    bad_input("image is " + std::to_string(mono8.cols) + "x" + std::to_string(mono8.rows) + " but the camera is " +
              std::to_string(camera_->width()) + "x" + std::to_string(camera_->height()));
  }
  if (has_prev_ && stamp_ns <= prev_stamp_ns_) {
    bad_input("image stamp " + std::to_string(stamp_ns) + " ns is not after the previous " +
              std::to_string(prev_stamp_ns_) + " ns");
  }
  if (R_prev_curr_C != nullptr && !R_prev_curr_C->allFinite()) bad_input("gyro rotation has non-finite entries");

  R_valid_[frame_index_ % kHistory] = has_prev_ && R_prev_curr_C != nullptr;
  if (R_valid_[frame_index_ % kHistory]) R_hist_[frame_index_ % kHistory] = *R_prev_curr_C;

  FrameResult result;
  result.stamp_ns = stamp_ns;
  const cv::Mat* image = &mono8;
  if (clahe_) {
    clahe_->apply(mono8, clahe_buffer_);
    image = &clahe_buffer_;
  }
  if (config_.presmooth_sigma_px > 0.0) {
    cv::GaussianBlur(*image, smooth_buffer_, cv::Size(0, 0), config_.presmooth_sigma_px, config_.presmooth_sigma_px,
                     cv::BORDER_REFLECT_101);
    image = &smooth_buffer_;
  }
  // Derivatives are stored with the pyramid: this frame is KLT's "previous" image twice (backward check now, forward
  // at the next frame), so they are computed once. No reuse of the input buffer: the caller may overwrite it.
  cv::buildOpticalFlowPyramid(*image, curr_pyramid_, cv::Size(config_.klt_window_px, config_.klt_window_px),
                              config_.klt_levels, true, cv::BORDER_REFLECT_101, cv::BORDER_CONSTANT, false);
  const auto t_pre = Clock::now();
  result.timing.preprocess_ms = ms_between(t_start, t_pre);

  if (has_prev_ && !tracks_.empty()) {
    std::vector<Eigen::Vector3d> f_prev;
    track_klt(*image, R_prev_curr_C, &f_prev, &result);
    const auto t_klt = Clock::now();
    result.timing.klt_ms = ms_between(t_pre, t_klt);
    reject_outliers(f_prev, R_prev_curr_C, &result);
    if (config_.ransac_span_frames > 0) reject_span_outliers(&result);
    result.timing.ransac_ms = ms_between(t_klt, Clock::now());
  }
  const auto t_detect = Clock::now();
  prune_and_detect(*image, &result);

  result.features.reserve(tracks_.size());
  for (const Track& t : tracks_) {
    result.features.push_back({t.id, Eigen::Vector2d(t.px.x, t.px.y), t.f_C, t.length});
  }
  std::swap(prev_pyramid_, curr_pyramid_);
  prev_stamp_ns_ = stamp_ns;
  has_prev_ = true;
  ++frame_index_;
  const auto t_end = Clock::now();
  result.timing.detect_ms = ms_between(t_detect, t_end);
  result.timing.total_ms = ms_between(t_start, t_end);
  return result;
}

void Frontend::predict(const Eigen::Matrix3d& R_prev_curr_C, std::vector<cv::Point2f>* guess) const {
  // A far point's bearing turns with the camera: f_curr = R_curr_prev f_prev (translation neglected).
  const Eigen::Matrix3d R_curr_prev = R_prev_curr_C.transpose();
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    Eigen::Vector2d uv;
    if (camera_->project(R_curr_prev * tracks_[i].f_C, &uv) == ProjectionStatus::kOk && camera_->in_image(uv)) {
      (*guess)[i] = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
    }  // else keep the previous pixel: the track will most likely leave the image anyway
  }
}

void Frontend::track_klt(const cv::Mat& image, const Eigen::Matrix3d* R_prev_curr_C,
                         std::vector<Eigen::Vector3d>* f_prev, FrameResult* result) {
  const std::size_t n = tracks_.size();
  std::vector<cv::Point2f> prev(n), guess(n);
  for (std::size_t i = 0; i < n; ++i) prev[i] = tracks_[i].px;
  guess = prev;
  if (R_prev_curr_C != nullptr) {
    predict(*R_prev_curr_C, &guess);
    result->stats.predicted = true;
  }
  const cv::Size window(config_.klt_window_px, config_.klt_window_px);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, config_.klt_max_iterations,
                              config_.klt_epsilon_px);
  std::vector<cv::Point2f> curr = guess;
  std::vector<unsigned char> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(prev_pyramid_, curr_pyramid_, prev, curr, status, error, window, config_.klt_levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);

  // Backward pass only for forward survivors, started from the inverse of the predicted flow (not from the answer).
  std::vector<std::size_t> alive;
  std::vector<cv::Point2f> fwd, back;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d uv(curr[i].x, curr[i].y);
    if (status[i] == 0 || !camera_->in_image(uv, kKltEdgePx)) {
      ++result->stats.lost_klt;
      continue;
    }
    alive.push_back(i);
    fwd.push_back(curr[i]);
    back.push_back(curr[i] - (guess[i] - prev[i]));
  }
  // The backward pass checks KLT against itself; with the reference alignment on, the alignment to the first frame's
  // patch is the stronger check (it sees drift the backward pass cannot) and the backward pass would only double the
  // KLT time, so it is skipped.
  const bool fb_check = config_.ref_window_px == 0;
  if (!fb_check) {
    for (std::size_t k = 0; k < alive.size(); ++k) back[k] = prev[alive[k]];
    status.assign(alive.size(), 1);
  }
  if (!fwd.empty() && fb_check) {
    cv::calcOpticalFlowPyrLK(curr_pyramid_, prev_pyramid_, fwd, back, status, error, window, config_.klt_levels, stop,
                             cv::OPTFLOW_USE_INITIAL_FLOW);
  }
  std::vector<Track> kept;
  kept.reserve(alive.size());
  f_prev->clear();
  const double fb2 = config_.fb_threshold_px * config_.fb_threshold_px;
  for (std::size_t k = 0; k < alive.size(); ++k) {
    const std::size_t i = alive[k];
    const cv::Point2f d = back[k] - prev[i];
    if (status[k] == 0 || d.dot(d) > fb2) {
      ++result->stats.lost_fb;
      continue;
    }
    Track t = tracks_[i];
    t.px = fwd[k];
    if (t.ref) {
      // KLT's answer is only the starting point: the first frame's patch decides where the feature is now.
      ReferencePatch::Warp warp;
      warp.A = t.ref_A;
      warp.t = Eigen::Vector2d(t.px.x, t.px.y);
      if (!t.ref->align(image, config_.ref_min_zncc, &warp) || !camera_->in_image(warp.t, kKltEdgePx)) {
        ++result->stats.lost_reference;
        continue;
      }
      t.ref_A = warp.A;
      t.px = cv::Point2f(static_cast<float>(warp.t.x()), static_cast<float>(warp.t.y()));
    }
    if (!camera_->unproject(Eigen::Vector2d(t.px.x, t.px.y), &t.f_C)) {
      ++result->stats.lost_klt;
      continue;
    }
    ++t.length;
    t.f_hist[frame_index_ % kHistory] = t.f_C;
    f_prev->push_back(tracks_[i].f_C);
    kept.push_back(t);
  }
  tracks_ = std::move(kept);
}

void Frontend::reject_outliers(const std::vector<Eigen::Vector3d>& f_prev, const Eigen::Matrix3d* R_prev_curr_C,
                               FrameResult* result) {
  std::vector<Eigen::Vector3d> f_curr(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) f_curr[i] = tracks_[i].f_C;
  RansacOptions options;
  options.threshold_rad = config_.ransac_threshold_px / camera_->intrinsics().fu;  // px -> rad at the centre
  options.confidence = config_.ransac_confidence;
  options.max_iterations = config_.ransac_max_iterations;
  options.seed = config_.ransac_seed;
  const bool known = R_prev_curr_C != nullptr && config_.ransac_model == FrontendConfig::RansacModel::kKnownRotation;
  const RansacResult ransac = known ? ransac_known_rotation(f_prev, f_curr, *R_prev_curr_C, options)
                                    : ransac_essential(f_prev, f_curr, options);
  std::vector<Track> kept;
  kept.reserve(ransac.num_inliers);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (ransac.inlier[i]) kept.push_back(tracks_[i]);
  }
  result->stats.lost_ransac = static_cast<int>(tracks_.size() - kept.size());
  tracks_ = std::move(kept);
}

void Frontend::reject_span_outliers(FrameResult* result) {
  // Tracks are seen in every frame of their life, so length > span means the bearing of span frames back is stored.
  const auto span = static_cast<std::uint32_t>(config_.ransac_span_frames);
  const std::size_t back = (frame_index_ + kHistory - span) % kHistory;
  // The rotation over the span, R_then_now = R_(then, then+1) ... R_(now-1, now), if the gyro gave every step.
  bool rotation_known = frame_index_ >= span;
  Eigen::Matrix3d R_then_now = Eigen::Matrix3d::Identity();
  for (std::uint32_t j = span; j >= 1 && rotation_known; --j) {
    const std::size_t slot = (frame_index_ + kHistory + 1 - j) % kHistory;
    rotation_known = R_valid_[slot];
    R_then_now = R_then_now * R_hist_[slot];
  }
  std::vector<std::size_t> old;
  std::vector<Eigen::Vector3d> f_then, f_now;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (tracks_[i].length <= span) continue;
    old.push_back(i);
    f_then.push_back(tracks_[i].f_hist[back]);
    f_now.push_back(tracks_[i].f_C);
  }
  RansacOptions options;
  options.threshold_rad = config_.ransac_threshold_px / camera_->intrinsics().fu;
  options.confidence = config_.ransac_confidence;
  options.max_iterations = config_.ransac_max_iterations;
  options.seed = config_.ransac_seed;
  const bool known = rotation_known && config_.ransac_model == FrontendConfig::RansacModel::kKnownRotation;
  const RansacResult ransac = known ? ransac_known_rotation(f_then, f_now, R_then_now, options)
                                    : ransac_essential(f_then, f_now, options);
  std::vector<bool> drop(tracks_.size(), false);
  for (std::size_t k = 0; k < old.size(); ++k) drop[old[k]] = !ransac.inlier[k];
  std::vector<Track> kept;
  kept.reserve(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (drop[i]) ++result->stats.lost_span;
    else kept.push_back(tracks_[i]);
  }
  tracks_ = std::move(kept);
}

void Frontend::prune_and_detect(const cv::Mat& image, FrameResult* result) {
  // Tracks that converged onto one spot (KLT windows sliding onto the same corner) are duplicates: of two tracks closer
  // than half the detection spacing, the longer one (more useful to the estimator) stays. Pruning at the full spacing
  // would cut healthy tracks whose distance merely shrinks under perspective.
  std::stable_sort(tracks_.begin(), tracks_.end(), [](const Track& a, const Track& b) { return a.length > b.length; });
  cv::Mat1b close(image.rows, image.cols, static_cast<unsigned char>(0));
  cv::Mat1b taken(image.rows, image.cols, static_cast<unsigned char>(0));
  std::vector<Track> kept;
  std::vector<cv::Point2f> existing;
  kept.reserve(config_.max_features);
  for (const Track& t : tracks_) {
    if (!is_free(close, t.px) || static_cast<int>(kept.size()) >= config_.max_features) {
      ++result->stats.pruned;
      continue;
    }
    mark_taken(close, t.px, 0.5 * config_.min_distance_px);
    mark_taken(taken, t.px, config_.min_distance_px);
    kept.push_back(t);
    existing.push_back(t.px);
  }
  result->stats.tracked = static_cast<int>(kept.size());
  const int wanted = config_.max_features - static_cast<int>(kept.size());
  for (const cv::Point2f& px : detect_bucketed(image, existing, taken, wanted, detection_config_, &barren_)) {
    Track t{next_id_, px, Eigen::Vector3d::UnitZ(), 1, nullptr, Eigen::Matrix2d::Identity(), {}};
    if (!camera_->unproject(Eigen::Vector2d(px.x, px.y), &t.f_C)) continue;  // outside the lens model's domain
    t.f_hist[frame_index_ % kHistory] = t.f_C;
    if (config_.ref_window_px > 0) t.ref = std::make_shared<const ReferencePatch>(image, px, config_.ref_window_px / 2);
    ++next_id_;
    kept.push_back(t);
    ++result->stats.detected;
  }
  tracks_ = std::move(kept);
}

}  // namespace twinslam::tracking
