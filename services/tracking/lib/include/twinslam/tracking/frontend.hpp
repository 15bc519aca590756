#pragma once
// The visual frontend: mono8 images in, tracked features (stable id, pixel, undistorted unit bearing, track length)
// out.
// Per frame (Frontend::track):
//   1. optional CLAHE, optional Gaussian presmoothing, image pyramid;
//   2. prediction: each feature's bearing rotated by the gyroscope's rotation since the previous frame and projected
//      with the camera model, as the KLT initial guess (features far from the camera barely move under translation
//      at 20 Hz, so rotation explains most of the image motion, and fast turns stay within KLT's basin);
//   3. pyramidal KLT forward; then the feature's first-frame patch is aligned to the image under an affine warp
//      from KLT's answer (reference_patch.hpp), so errors do not accumulate from frame to frame, and a track whose
//      patch no longer matches its reference (occlusion, a slid silhouette) is dropped. With the alignment off
//      (ref_window_px = 0), KLT runs backward from its answer instead and a track survives if it comes back within
//      fb_threshold_px of where it started;
//   4. RANSAC on bearings drops matches that violate the epipolar geometry (ransac.hpp), once against the previous
//      frame and once against the frame ransac_span_frames back (slow slides need the longer baseline);
//   5. tracks closer than min_distance_px / 2 to a longer track are dropped as duplicates, then Shi-Tomasi corners at
//      least min_distance_px from every track fill the grid buckets back up to max_features (detector.hpp), each
//      with a new id.
// Not thread-safe; one Frontend per camera.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>  // cv::CLAHE

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/tracking/frontend_config.hpp"

namespace twinslam::tracking {

class ReferencePatch;

struct TrackedFeature {
  std::uint64_t id = 0;                                // unique over the Frontend's life, never reused
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();        // distorted pixel [px], OpenCV convention
  Eigen::Vector3d bearing_C = Eigen::Vector3d::UnitZ();  // undistorted unit bearing in C: CameraModel::unproject(uv)
  std::uint32_t track_length = 1;                      // frames this feature has been seen, 1 on first detection
};

// Wall-clock time spent in each step of track() [ms].
struct FrameTiming {
  double preprocess_ms = 0;  // CLAHE and pyramid
  double klt_ms = 0;         // prediction, KLT forward and backward, bearings
  double ransac_ms = 0;
  double detect_ms = 0;      // min-distance pruning and top-up detection
  double total_ms = 0;       // the whole call
};

// What happened to the previous frame's tracks, and how many were added.
struct FrameStats {
  int lost_klt = 0;         // KLT did not converge, left the image, or the pixel has no bearing
  int lost_fb = 0;          // failed the forward-backward check
  int lost_reference = 0;   // the first frame's patch no longer aligns to the image (see FrontendConfig::ref_*)
  int lost_ransac = 0;      // epipolar outliers
  int lost_span = 0;        // epipolar outliers against the frame FrontendConfig::ransac_span_frames back
  int pruned = 0;           // closer than min_distance_px / 2 to a longer track
  int tracked = 0;          // survivors carried over from the previous frame
  int detected = 0;         // new features
  bool predicted = false;   // a gyro rotation was used as the KLT initial guess
};

struct FrameResult {
  std::int64_t stamp_ns = 0;
  std::vector<TrackedFeature> features;  // survivors first (longest tracks first), then new detections
  FrameTiming timing;
  FrameStats stats;
};

class Frontend {
 public:
  // Throws InputError if camera is null or the config is invalid.
  Frontend(std::shared_ptr<const CameraModel> camera, const FrontendConfig& config = {});

  // mono8: CV_8UC1 of the camera's resolution. R_prev_curr_C (optional): the camera's rotation since the previous
  // frame, mapping camera coordinates at this frame to the previous one (gyro_rotation_C() computes it); null = no
  // prediction. Throws InputError on a wrong image type/size or a stamp not after the previous one.
  FrameResult track(std::int64_t stamp_ns, const cv::Mat& mono8, const Eigen::Matrix3d* R_prev_curr_C = nullptr);

  // Forgets all tracks (ids continue to increase, so they stay unique).
  void reset();

  const FrontendConfig& config() const { return config_; }
  const CameraModel& camera() const { return *camera_; }

 private:
  static constexpr std::size_t kHistory = 8;
  struct Track {
    std::uint64_t id;
    cv::Point2f px;
    Eigen::Vector3d f_C;
    std::uint32_t length;
    std::shared_ptr<const ReferencePatch> ref;              // appearance at the first frame; null when disabled
    Eigen::Matrix2d ref_A = Eigen::Matrix2d::Identity();  // linear part of the reference-to-image warp
    std::array<Eigen::Vector3d, kHistory> f_hist;         // f_C of recent frames, at [frame index % kHistory]
  };
  static_assert(kHistory > 7, "ransac_span_frames may reach 7");

  // Steps of track(); each updates tracks_ and the counts in result->stats.
  void predict(const Eigen::Matrix3d& R_prev_curr_C, std::vector<cv::Point2f>* guess) const;
  // Leaves the survivors in tracks_ and their bearings at the previous frame in *f_prev (same order).
  void track_klt(const cv::Mat& image, const Eigen::Matrix3d* R_prev_curr_C, std::vector<Eigen::Vector3d>* f_prev,
                 FrameResult* result);
  void reject_outliers(const std::vector<Eigen::Vector3d>& f_prev, const Eigen::Matrix3d* R_prev_curr_C,
                       FrameResult* result);
  void reject_span_outliers(FrameResult* result);
  void prune_and_detect(const cv::Mat& image, FrameResult* result);

  std::shared_ptr<const CameraModel> camera_;
  FrontendConfig config_;
  FrontendConfig detection_config_;  // config_ with min_eigenvalue scaled for the presmoothing
  cv::Ptr<cv::CLAHE> clahe_;  // null when config_.clahe is off
  cv::Mat clahe_buffer_;
  cv::Mat smooth_buffer_;     // the presmoothed image (config_.presmooth_sigma_px)
  std::vector<cv::Mat> prev_pyramid_, curr_pyramid_;
  std::vector<Track> tracks_;
  std::vector<int> barren_;  // per grid bucket: detection visits left to skip (see detector.hpp)
  std::int64_t prev_stamp_ns_ = 0;
  bool has_prev_ = false;
  std::uint64_t next_id_ = 1;
  std::uint64_t frame_index_ = 0;  // track() calls so far
  // Gyro rotation R_prev_curr_C given with each of the recent frames, at [frame index % kHistory]; for the span RANSAC.
  std::array<Eigen::Matrix3d, kHistory> R_hist_;
  std::array<bool, kHistory> R_valid_{};
};

}  // namespace twinslam::tracking
