#pragma once
// Internal state of SlidingWindowEstimator, shared by its source files (not an API).
#include <array>
#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <unordered_map>

#include "twinslam/estimator/landmark.hpp"
#include "twinslam/estimator/marginalization.hpp"
#include "twinslam/estimator/motion_init.hpp"
#include "twinslam/estimator/preintegration.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/estimator/residual_term.hpp"
#include "twinslam/estimator/state_prior.hpp"
#include "twinslam/estimator/world_alignment.hpp"

namespace twinslam::estimator {

struct WindowFrame {
  std::int64_t id = 0;
  std::int64_t stamp_ns = 0;
  bool keyframe = false;
  bool stationary = false;  // features stood still since the last keyframe: zero-velocity factor (see config)
  std::array<double, kPoseSize> pose{};             // Ceres block [p_L, q_LB xyzw]
  std::array<double, kSpeedBiasSize> speed_bias{};  // Ceres block [v_L, b_g, b_a]
  std::unordered_map<std::int64_t, Eigen::Vector3d> bearings;  // feature id -> f_C
  std::shared_ptr<Preintegration> imu_from_prev;    // previous frame -> this one (null for the oldest)
  Eigen::Isometry3d T_LB() const { return pose_from_block(pose.data()); }
};

struct WindowLandmark {
  InverseDepthLandmark lm;    // anchor_keyframe = WindowFrame::id of the anchor
  double rho = 0.1;           // Ceres block (lm.rho is synced after each solve)
  double mean_error_px = 0.0; // after the last solve
  double parallax_deg = 0.0;  // at triangulation
};

struct WindowState {
  SlidingWindowConfig config;
  std::vector<ImuSample> imu;                 // sorted; trimmed to what the window needs
  std::deque<std::unique_ptr<WindowFrame>> frames;  // oldest first; only the last may be a non-keyframe
  std::map<std::int64_t, WindowLandmark> landmarks;  // triangulated, by feature id
  std::shared_ptr<MarginalizationPrior> prior;  // shared with the term list that feeds it to Ceres
  bool first_prior_active = false;            // frames.front() still carries the initial-state prior
  ImuState first_prior_state;
  StatePriorSigmas first_prior_sigmas;        // of the initialization that started the window
  bool initialized = false;
  EstimatorStatus idle_status = EstimatorStatus::kInitializing;
  std::optional<ImuState> pending_init;
  std::optional<StatePriorSigmas> pending_init_sigmas;  // of pending_init (default: static_init_prior_sigmas)
  std::deque<MotionInitFrame> rest_frames;    // while initializing: the frames of the last static_window_s (stillness)
  std::deque<MotionInitFrame> init_frames;    // while initializing: the last motion_init.window_s of frames
  std::int64_t first_frame_ns = -1;           // first frame seen since the last (re)start
  std::int64_t last_frame_ns = -1;
  std::int64_t next_frame_id = 0;
  std::optional<LocalMapEstimate> local_map;
  LandmarkHorizon horizon;                    // landmarks of recent keyframes for the LocalMap
  std::vector<std::shared_ptr<WindowFactorProvider>> providers;

  // World alignment (world_alignment.hpp): the block, its prior from set_world_alignment(), and whether any term has
  // acted on it yet (then T_WB = T_WL T_LB is in W and the odometry says ODOM_ALIGNED).
  std::array<double, kWorldAlignmentSize> T_WL{};
  std::optional<ResidualTerm> world_prior;
  bool world_aligned = false;

  // Correction of the camera rotation (camera_calibration.hpp), estimated when config.camera_rotation_sigma_deg > 0.
  // Kept across re-initializations: it belongs to the sensor, not to L.
  std::array<double, 3> phi_BC{};
  // Correction of the intrinsics in bearing space (lens_calibration.hpp), estimated when the config's lens_*_sigma
  // are > 0; kept across re-initializations like phi_BC.
  std::array<double, 4> lens{};
};

// Result of one window solve (window_solver.cpp).
struct SolveSummary {
  double median_error_px = 0.0;  // over all reprojection factors before outlier removal
  int outliers_removed = 0;
};

// The camera in the body as the window estimates it now (the nominal config.T_BC unless calibrated online).
Eigen::Isometry3d camera_T_BC(const WindowState& s);
bool calibrates_camera(const WindowState& s);
bool calibrates_lens(const WindowState& s);
// The prior sigmas of the lens block (lens_calibration.hpp) from the config's lens_* keys.
std::array<double, 4> lens_sigmas(const SlidingWindowConfig& c);
// Whether the camera's optical axis spans config.lens_excitation_deg over the window's frames, config.lens_settle_s
// after the (re)start; else the lens is held in the solve (straight forward flight cannot tell k1 from depth and
// scale, nor can a window whose biases and scale are still settling).
bool lens_excited(const WindowState& s);
// Whether this solve estimates the lens: calibrated online and excited. Else the reprojections use the fixed factor on
// lens_bearing()s and the lens block, if the marginalization prior still holds it, is constant.
bool lens_free(const WindowState& s);
// A stated bearing through the lens correction the window estimates now (f itself unless calibrated online).
Eigen::Vector3d lens_bearing(const WindowState& s, const Eigen::Vector3d& f);
// Prior sigmas of the first keyframe after a static initialization (config's init_* values).
StatePriorSigmas static_init_prior_sigmas(const SlidingWindowConfig& c);
// The window's frame with this id, or null.
WindowFrame* find_frame(WindowState& s, std::int64_t id);
// The state blocks handed to providers (window_factor_provider.hpp).
WindowBlocks window_blocks(WindowState& s);
// The one list of residual terms of the window as it is now (window_terms.cpp): what the solve minimizes and what
// the marginalization linearizes.
std::vector<ResidualTerm> build_window_terms(WindowState& s);
// The terms and blocks that marginalizing the oldest keyframe eliminates (window_marginalization.cpp): every term
// acting on its pose or speed/bias block, the previous marginalization prior (replaced by the new one), and as blocks
// the keyframe's two blocks plus the inverse depths anchored in it.
struct MarginalizationSelection {
  std::vector<ResidualTerm> terms;
  std::vector<double*> blocks;
};
MarginalizationSelection select_for_marginalization(WindowState& s, const std::vector<ResidualTerm>& terms);
// Builds the problem from `s`, solves it, syncs landmarks, removes outlier observations and bad landmarks.
SolveSummary solve_window(WindowState& s);
// Triangulates features seen in at least config.min_observations window frames that are not landmarks yet.
void triangulate_new_landmarks(WindowState& s);
// Re-anchors the oldest keyframe's landmarks, marginalizes it into the prior and removes it from the window.
void marginalize_oldest(WindowState& s);
// The window's landmarks in L with quality values.
std::vector<LandmarkEstimate> window_landmarks(const WindowState& s);

}  // namespace twinslam::estimator
