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
// L is gravity-aligned with the initial pose's yaw = 0 and position 0. The world alignment T_WL (4 DoF,
// world_alignment.hpp) is a state of the window too: global measurements act on it through providers' terms, and
// set_world_alignment() gives it an initial value and prior. The window starts from a static initialization
// at rest (static_init.hpp) or, in motion, from the closed-form visual-inertial one (motion_init.hpp). Pure library, no DDS.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/state_prior.hpp"
#include "twinslam/estimator/sliding_window_config.hpp"
#include "twinslam/estimator/window_factor_provider.hpp"
#include "twinslam/estimator/world_alignment.hpp"

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
  // World alignment after this frame's solve; T_WB = T_WL T_LB is in W only when `aligned` (some term has acted on
  // T_WL), otherwise T_WL is the identity guess and T_WB is just T_LB.
  Eigen::Isometry3d T_WL = Eigen::Isometry3d::Identity();
  bool aligned = false;
  double estimator_ms = 0.0;                      // wall time spent in add_frame [ms]
  double imu_gap_s = 0.0;  // longest IMU gap (> config imu_gap_s) since the previous frame, 0 if none [s]
  bool few_features = false;  // fewer than min_keyframe_features: the pose is the IMU's prediction (not a keyframe)
};


struct LocalMapEstimate {
  std::int64_t keyframe_stamp_ns = 0;
  Eigen::Isometry3d T_LB = Eigen::Isometry3d::Identity();  // the keyframe's pose
  Eigen::Isometry3d T_WL = Eigen::Isometry3d::Identity();  // current alignment (identity until aligned)
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

  // Starts the window at the next frame with `state` instead of waiting for rest (tests; a resumed checkpoint,
  // resume.hpp). The prior of the first keyframe has `sigmas`, by default those after a static initialization.
  void initialize_next_frame(const ImuState& state, const std::optional<StatePriorSigmas>& sigmas = std::nullopt);
  void add_factor_provider(std::shared_ptr<WindowFactorProvider> provider);

  // Sets T_WL (its yaw and translation; L and W are gravity-aligned) with a prior of these sigmas, e.g. from the
  // initial GNSS alignment (paper eq. 11). Information on T_WL from earlier terms is first marginalized out of the
  // window's prior, so a re-alignment after a long outage replaces the old alignment instead of fighting it. Takes
  // effect from the next frame; before the window exists it is kept for it. Throws InputError on bad sigmas.
  void set_world_alignment(const Eigen::Isometry3d& T_WL, const WorldAlignmentSigmas& sigmas);
  Eigen::Isometry3d world_alignment() const;
  bool world_aligned() const;

  // Marginal covariance of a window frame's pose (by stamp) from the linearized window at its current estimate, in
  // the pose tangent [dp_L (3, m), dtheta_B (3, rad, right perturbation)] (translation first); nullopt if no frame
  // has that stamp. A dense inverse of the window's information: for diagnostics, tests and gating, not per frame.
  std::optional<Eigen::Matrix<double, 6, 6>> pose_covariance(std::int64_t stamp_ns) const;
  // The same for T_WB = T_WL T_LB, including the uncertainty of T_WL: [dp_W (3, m), dtheta_B (3, rad)]; equals
  // pose_covariance() while T_WL is not estimated.
  std::optional<Eigen::Matrix<double, 6, 6>> pose_covariance_world(std::int64_t stamp_ns) const;
  // Marginal covariance of T_WL in its block order [p_WL (m), yaw_WL (rad)]; nullopt until some term acts on T_WL.
  std::optional<Eigen::Matrix4d> world_alignment_covariance() const;
  // Stamps of the window's frames, oldest first (the last may be a non-keyframe).
  std::vector<std::int64_t> window_stamps() const;

  // The internal state (sliding_window_state.hpp), for tests and diagnostics only.
  WindowState& internal_state() { return *s_; }

  // The window's landmarks, set by the last add_frame if that frame became a keyframe (empty otherwise).
  const std::optional<LocalMapEstimate>& local_map() const;
  std::size_t keyframe_count() const;
  std::size_t landmark_count() const;     // triangulated landmarks in the window
  // The camera in the body as estimated now: the configured T_BC with its online rotation correction (the configured
  // T_BC itself while config().camera_rotation_sigma_deg is 0).
  Eigen::Isometry3d camera_extrinsics() const;
  // The window's correction of the stated intrinsics (lens_calibration.hpp: relative focal, k1 [1/rad^2], principal
  // point over focal [rad] x, y); zeros while config().lens_*_sigma are 0.
  std::array<double, 4> lens_correction() const;
  const SlidingWindowConfig& config() const;

 private:
  std::unique_ptr<WindowState> s_;
};

}  // namespace twinslam::estimator
