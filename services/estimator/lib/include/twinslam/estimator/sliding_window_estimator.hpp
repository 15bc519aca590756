#pragma once
// The sliding-window visual-inertial estimator (issue 5; equation (1) of the paper without the map term): keyframes
// with IMU preintegration factors between them, bearing reprojection factors of anchored-inverse-depth landmarks, and
// a marginalization prior from the keyframes that left the window (OKVIS / VINS-Mono style keyframe window).
//
// Per frame: the newest frame joins the window predicted by the IMU; the previous newest frame, if it did not become a
// keyframe, is dropped with its observations first (paper Sec. III-B); new landmarks are triangulated; the window is
// solved with bounded iterations and time; outliers are removed by reprojection error; divergence resets the estimator.
// When a keyframe makes the window exceed its length, the oldest keyframe's landmarks are re-anchored and the keyframe
// is marginalized into a MarginalizationPrior.
//
// L is gravity-aligned with the initial pose's yaw = 0 and position 0. The window starts from a static initialization
// at rest (static_init.hpp) or, in motion, from the closed-form visual-inertial one (motion_init.hpp). Pure library, no DDS.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/sliding_window_config.hpp"
#include "twinslam/estimator/window_factor_provider.hpp"

namespace twinslam::estimator {

struct FeatureBearing {
  std::int64_t id = -1;                              // track id, stable over frames
  Eigen::Vector3d f_C = Eigen::Vector3d::UnitZ();    // unit bearing in the camera C
};

enum class EstimatorStatus { kInitializing, kTracking, kReinitializing };

struct FrameEstimate {
  std::int64_t stamp_ns = 0;
  EstimatorStatus status = EstimatorStatus::kInitializing;
  bool keyframe = false;
  bool init_timed_out = false;  // still initializing init_timeout_s after the first frame (neither rest nor motion init)
  Eigen::Isometry3d T_LB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_L = Eigen::Vector3d::Zero();  // [m/s]
  ImuBias bias;
  double estimator_ms = 0.0;                      // wall time spent in add_frame [ms]
};

struct LandmarkEstimate {
  std::int64_t id = -1;
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  // [m]
  double quality = 0.0;                           // [0, 1]: observations, parallax, reprojection error
};

struct LocalMapEstimate {
  std::int64_t keyframe_stamp_ns = 0;
  Eigen::Isometry3d T_LB = Eigen::Isometry3d::Identity();  // the keyframe's pose
  std::vector<LandmarkEstimate> landmarks;
};

struct WindowState;  // internal (sliding_window_state.hpp)

class SlidingWindowEstimator {
 public:
  explicit SlidingWindowEstimator(const SlidingWindowConfig& config = {});
  ~SlidingWindowEstimator();
  SlidingWindowEstimator(const SlidingWindowEstimator&) = delete;
  SlidingWindowEstimator& operator=(const SlidingWindowEstimator&) = delete;

  // IMU samples in stamp order; an out-of-order or non-finite sample throws twinslam::InputError.
  void add_imu(const ImuSample& sample);
  // One camera frame's tracked features (bearings only). Frames must come in stamp order (else InputError). IMU
  // should cover the stamp; if it does not, the last sample is held up to it.
  FrameEstimate add_frame(std::int64_t stamp_ns, const std::vector<FeatureBearing>& features);

  // Starts the window at the next frame with `state` instead of waiting for rest (tests; a future motion-based or
  // GNSS initializer). The prior of the first keyframe is the same as after static initialization.
  void initialize_next_frame(const ImuState& state);
  void add_factor_provider(std::shared_ptr<WindowFactorProvider> provider);

  // The window's landmarks, set by the last add_frame if that frame became a keyframe (empty otherwise).
  const std::optional<LocalMapEstimate>& local_map() const;
  std::size_t keyframe_count() const;
  std::size_t landmark_count() const;     // triangulated landmarks in the window
  const SlidingWindowConfig& config() const;

 private:
  std::unique_ptr<WindowState> s_;
};

}  // namespace twinslam::estimator
