// Frame flow of the sliding window: initialization, IMU prediction, keyframe decision, solve, divergence, sliding.
#include "twinslam/estimator/sliding_window_estimator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>


#include "twinslam/core/error.hpp"
#include "twinslam/estimator/keyframe_policy.hpp"
#include "twinslam/estimator/motion_init.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"
#include "twinslam/estimator/static_init.hpp"
#include "visual_rest.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kMaxGyro_radps = 1e3, kMaxAccel_mps2 = 1e4;  // add_imu: no IMU measures beyond these

template <class Block>
bool all_finite(const Block& block) {
  return std::all_of(block.begin(), block.end(), [](double v) { return std::isfinite(v); });
}

bool window_finite_frame(const WindowFrame& f) { return all_finite(f.pose) && all_finite(f.speed_bias); }

ImuState frame_state(const WindowFrame& f) { return unpack(f.pose.data(), f.speed_bias.data()); }

FrameEstimate make_estimate(const WindowState& s, const WindowFrame& f, EstimatorStatus status) {
  FrameEstimate e;
  e.T_WL = world_alignment_pose(s.T_WL.data());
  e.aligned = s.world_aligned;
  e.stamp_ns = f.stamp_ns;
  e.status = status;
  e.keyframe = f.keyframe;
  const ImuState st = frame_state(f);
  e.T_LB = f.T_LB();
  e.v_L = st.v_L;
  e.bias = st.bias;
  return e;
}

// IMU samples covering [t0, t1]; when the buffer ends before t1 the last sample is held up to t1 (zero-order hold),
// so a frame whose IMU is late (the node waits at most 100 ms) is still predicted.
std::vector<ImuSample> covering(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1) {
  const auto span = covering_samples(imu, t0, t1);
  std::vector<ImuSample> out(span.begin(), span.end());
  if (!out.empty() && out.back().stamp_ns < t1) {
    ImuSample hold = out.back();
    hold.stamp_ns = t1;
    out.push_back(hold);
  }
  return out;
}

// The longest step between the IMU samples that cover (t0, t1], counting the hold to t1 when the buffer ends first
// (what covering() integrates) [s]; 0 without samples.
double longest_imu_step_s(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1) {
  const auto span = covering_samples(imu, t0, t1);  // per frame: no copy of the samples
  if (span.empty()) return 0.0;
  std::int64_t longest = std::max<std::int64_t>(0, t1 - span.back().stamp_ns);
  for (std::size_t k = 1; k < span.size(); ++k) longest = std::max(longest, span[k].stamp_ns - span[k - 1].stamp_ns);
  return 1e-9 * static_cast<double>(longest);
}

// x_j from x_i and the preintegrated delta (Forster eq. 33 without noise), g_L = (0, 0, -|g|).
void predict(const WindowFrame& prev, const Preintegration& pre, double gravity, WindowFrame& next) {
  const ImuState i = frame_state(prev);
  const PreintegratedDelta d = pre.corrected(i.bias);
  const Eigen::Vector3d g(0, 0, -gravity);
  const double dt = pre.dt();
  const Eigen::Matrix3d R_i = i.q_LB.toRotationMatrix();
  ImuState j = i;
  j.q_LB = Eigen::Quaterniond(R_i * d.R).normalized();
  j.v_L = i.v_L + g * dt + R_i * d.v;
  j.p_L = i.p_L + i.v_L * dt + 0.5 * g * dt * dt + R_i * d.p;
  pack(j, next.pose.data(), next.speed_bias.data());
}

PreintegrationConfig preintegration_config(const SlidingWindowConfig& c) {
  PreintegrationConfig p;
  p.noise = c.imu;
  p.gap_s = c.imu_gap_s;
  p.gap_gyro_sigma = c.imu_gap_gyro_sigma;
  p.gap_accel_sigma = c.imu_gap_accel_sigma;
  return p;
}

void start_window(WindowState& s, std::int64_t stamp_ns, const ImuState& state, const StatePriorSigmas& sigmas,
                  const std::vector<FeatureBearing>& features) {
  auto f = std::make_unique<WindowFrame>();
  f->id = s.next_frame_id++;
  f->stamp_ns = stamp_ns;
  f->keyframe = true;
  pack(state, f->pose.data(), f->speed_bias.data());
  for (const auto& b : features) f->bearings[b.id] = b.f_C;
  s.frames.push_back(std::move(f));
  s.first_prior_active = true;
  s.first_prior_state = state;
  s.first_prior_sigmas = sigmas;
  s.initialized = true;
  s.init_frames.clear();
}

// Clears the window after divergence; the next static initialization restarts it.
void reset(WindowState& s) {
  s.frames.clear();
  s.landmarks.clear();
  s.prior.reset();
  s.first_prior_active = false;
  s.initialized = false;
  s.idle_status = EstimatorStatus::kReinitializing;
  s.first_frame_ns = -1;
  s.init_frames.clear();
  s.rest_frames.clear();
  s.horizon.clear();  // its landmarks are in the old L
  // L is defined anew by the next initialization, so the old T_WL means nothing for it: global inputs align again.
  s.T_WL.fill(0.0);
  s.world_prior.reset();
  s.world_aligned = false;
}

// Every parameter block Ceres would get is finite. Ceres aborts the process (a CHECK) on a non-finite one, so a window
// that is not (found by the dds_estimator fuzz target) restarts as after divergence instead of reaching it.
bool window_finite(const WindowState& s) {
  for (const auto& f : s.frames) {
    if (!window_finite_frame(*f)) return false;
  }
  for (const auto& [id, lm] : s.landmarks) {
    if (!std::isfinite(lm.rho)) return false;
  }
  return all_finite(s.T_WL);
}

bool diverged(const WindowState& s, const SolveSummary& summary) {
  const auto& c = s.config;
  for (const auto& f : s.frames) {
    const ImuState st = frame_state(*f);
    if (!st.p_L.allFinite() || !st.v_L.allFinite() || st.v_L.norm() > c.max_speed_mps ||
        st.bias.gyro.norm() > c.max_gyro_bias_radps || st.bias.accel.norm() > c.max_accel_bias_mps2) {
      return true;
    }
  }
  return summary.median_error_px > c.max_median_reprojection_px;
}

// Keyframe decision for the newest frame against the last keyframe (keyframe_policy.hpp), plus a time limit.
bool is_keyframe(const WindowState& s, const WindowFrame& kf, const WindowFrame& cur) {
  const auto& c = s.config;
  if (static_cast<int>(cur.bearings.size()) < c.min_keyframe_features) return false;
  if (1e-9 * static_cast<double>(cur.stamp_ns - kf.stamp_ns) >= c.max_keyframe_interval_s) return true;
  std::vector<TrackedBearing> tracked;
  for (const auto& [id, f_Cc] : cur.bearings) {
    const auto it = kf.bearings.find(id);
    if (it != kf.bearings.end()) tracked.push_back({it->second, f_Cc});
  }
  KeyframeInput in;
  in.tracked = tracked;
  in.keyframe_features = kf.bearings.size();
  const Eigen::Matrix3d R_BC = camera_T_BC(s).linear();
  const Eigen::Matrix3d dR = kf.T_LB().linear().transpose() * cur.T_LB().linear();
  in.R_CkCc = R_BC.transpose() * dR * R_BC;
  KeyframePolicyConfig kc = c.keyframe;
  kc.focal_px = c.focal_px;
  return decide_keyframe(kc, in).is_keyframe;
}

// Zero-velocity detection against the last keyframe (config: zero_velocity_*): mean raw bearing change [px].
bool is_stationary(const WindowState& s, const WindowFrame& kf, const WindowFrame& cur) {
  const auto& c = s.config;
  if (!c.zero_velocity || 1e-9 * static_cast<double>(cur.stamp_ns - kf.stamp_ns) < c.zero_velocity_min_interval_s) {
    return false;
  }
  double sum = 0.0;
  int n = 0;
  for (const auto& [id, f_Cc] : cur.bearings) {
    const auto it = kf.bearings.find(id);
    if (it == kf.bearings.end()) continue;
    sum += std::atan2(f_Cc.cross(it->second).norm(), f_Cc.dot(it->second));
    ++n;
  }
  return n >= c.zero_velocity_min_tracks && c.focal_px * sum / n < c.zero_velocity_max_motion_px;
}

// Repropagates the preintegrations whose linearization bias is far from the current estimate (Forster eq. 44 holds
// only near it).
void repropagate(WindowState& s) {
  for (std::size_t k = 1; k < s.frames.size(); ++k) {
    if (s.frames[k]->imu_from_prev) s.frames[k]->imu_from_prev->repropagate_if_needed(frame_state(*s.frames[k - 1]).bias);
  }
}

void trim_imu(WindowState& s) {
  if (s.frames.empty()) {
    // Keep what the static and motion initializations need.
    const double keep_s = std::max(s.config.static_window_s, s.config.motion_init.window_s) + 1.0;
    const auto keep_ns = static_cast<std::int64_t>(keep_s * 1e9);
    if (!s.imu.empty() && s.imu.back().stamp_ns - s.imu.front().stamp_ns > 2 * keep_ns) {
      const std::int64_t t = s.imu.back().stamp_ns - keep_ns;
      s.imu.erase(s.imu.begin(), std::find_if(s.imu.begin(), s.imu.end(), [&](const ImuSample& x) { return x.stamp_ns >= t; }));
    }
    return;
  }
  // Only IMU after the newest keyframe is needed again (older preintegrations store their samples).
  std::int64_t t = s.frames.back()->stamp_ns;
  for (const auto& f : s.frames) if (f->keyframe) t = f->stamp_ns;
  auto it = std::find_if(s.imu.begin(), s.imu.end(), [&](const ImuSample& x) { return x.stamp_ns > t; });
  if (it != s.imu.begin()) --it;
  s.imu.erase(s.imu.begin(), it);
}


// Buffers the frame and, once motion_init.min_span_s of frames are there, tries the closed-form initialization.
std::optional<MotionInitResult> try_init_in_motion(WindowState& s, std::int64_t stamp_ns,
                                                   const std::vector<FeatureBearing>& features) {
  MotionInitConfig c = s.config.motion_init;
  c.pixel_sigma = s.config.pixel_sigma;
  MotionInitFrame frame;
  frame.stamp_ns = stamp_ns;
  for (const auto& b : features) frame.bearings[b.id] = b.f_C;
  s.init_frames.push_back(std::move(frame));
  const auto window_ns = static_cast<std::int64_t>(c.window_s * 1e9);
  while (s.init_frames.size() > 1 && stamp_ns - s.init_frames.front().stamp_ns > window_ns) s.init_frames.pop_front();
  const std::vector<MotionInitFrame> frames(s.init_frames.begin(), s.init_frames.end());
  return try_motion_init(frames, s.imu, camera_T_BC(s), s.config.imu, s.config.gravity_mps2, s.config.focal_px, c);
}
}  // namespace

SlidingWindowEstimator::SlidingWindowEstimator(const SlidingWindowConfig& config) : s_(std::make_unique<WindowState>()) {
  config.validate();
  s_->config = config;
  s_->horizon = LandmarkHorizon(config.local_map);
}

SlidingWindowEstimator::~SlidingWindowEstimator() = default;

void SlidingWindowEstimator::add_imu(const ImuSample& sample) {
  if (!sample.gyro_B.allFinite() || !sample.accel_B.allFinite()) {
    throw InputError("imu sample at " + std::to_string(sample.stamp_ns) + " ns: not finite");
  }
  // Beyond what any IMU measures (MEMS ranges end near 70 rad/s and a few hundred g): corrupt, and integrating it
  // would overflow the state.
  if (sample.gyro_B.norm() > kMaxGyro_radps || sample.accel_B.norm() > kMaxAccel_mps2) {
    throw InputError("imu sample at " + std::to_string(sample.stamp_ns) + " ns: beyond any IMU's range (" +
                     std::to_string(kMaxGyro_radps) + " rad/s, " + std::to_string(kMaxAccel_mps2) + " m/s^2)");
  }
  if (!s_->imu.empty() && sample.stamp_ns <= s_->imu.back().stamp_ns) {
    throw InputError("imu sample at " + std::to_string(sample.stamp_ns) + " ns: timestamp not increasing");
  }
  s_->imu.push_back(sample);
}

void SlidingWindowEstimator::initialize_next_frame(const ImuState& state, const std::optional<StatePriorSigmas>& sigmas) {
  s_->pending_init = state;
  s_->pending_init_sigmas = sigmas;
}

void SlidingWindowEstimator::add_factor_provider(std::shared_ptr<WindowFactorProvider> provider) {
  s_->providers.push_back(std::move(provider));
}

const std::optional<LocalMapEstimate>& SlidingWindowEstimator::local_map() const { return s_->local_map; }
std::size_t SlidingWindowEstimator::landmark_count() const { return s_->landmarks.size(); }

Eigen::Isometry3d SlidingWindowEstimator::camera_extrinsics() const { return camera_T_BC(*s_); }
std::array<double, 4> SlidingWindowEstimator::lens_correction() const { return s_->lens; }
const SlidingWindowConfig& SlidingWindowEstimator::config() const { return s_->config; }
std::size_t SlidingWindowEstimator::keyframe_count() const {
  return static_cast<std::size_t>(std::count_if(s_->frames.begin(), s_->frames.end(), [](const auto& f) { return f->keyframe; }));
}

FrameEstimate SlidingWindowEstimator::add_frame(std::int64_t stamp_ns, const std::vector<FeatureBearing>& features) {
  const auto t0 = std::chrono::steady_clock::now();
  WindowState& s = *s_;
  if (s.last_frame_ns >= 0 && stamp_ns <= s.last_frame_ns) {
    throw InputError("frame at " + std::to_string(stamp_ns) + " ns: timestamp not increasing");
  }
  for (const auto& b : features) {
    if (!b.f_C.allFinite() || std::abs(b.f_C.norm() - 1.0) > 1e-3) {
      throw InputError("frame at " + std::to_string(stamp_ns) + " ns: feature " + std::to_string(b.id) +
                       " has no unit bearing");
    }
  }
  // An IMU gap since the previous frame is reported with this frame (preintegration.hpp integrates across it).
  const double imu_step_s = s.last_frame_ns >= 0 ? longest_imu_step_s(s.imu, s.last_frame_ns, stamp_ns) : 0.0;
  s.last_frame_ns = stamp_ns;
  s.local_map.reset();
  auto finish = [&](FrameEstimate e) {
    e.estimator_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    e.imu_gap_s = imu_step_s > s.config.imu_gap_s ? imu_step_s : 0.0;
    e.few_features = s.initialized && static_cast<int>(features.size()) < s.config.min_keyframe_features;
    trim_imu(s);
    return e;
  };

  if (!s.initialized) {
    if (s.first_frame_ns < 0) s.first_frame_ns = stamp_ns;
    std::optional<ImuState> init = s.pending_init;
    s.pending_init.reset();
    const bool still = visually_still(s, stamp_ns, features);
    StatePriorSigmas sigmas = s.pending_init_sigmas.value_or(static_init_prior_sigmas(s.config));
    s.pending_init_sigmas.reset();
    if (!init && still) {
      const auto end = std::upper_bound(s.imu.begin(), s.imu.end(), stamp_ns,
                                        [](std::int64_t t, const ImuSample& x) { return t < x.stamp_ns; });
      const std::vector<ImuSample> upto(s.imu.begin(), end);
      if (const auto rest = try_static_init(upto, s.config.static_init())) {
        init = ImuState{};
        init->q_LB = rest->q_LB;
        init->bias = rest->bias;
      }
    }
    if (!init && s.config.motion_init.enabled) {
      if (const auto m = try_init_in_motion(s, stamp_ns, features)) {
        init = m->state;
        sigmas.velocity_mps = std::max(m->velocity_sigma_mps, s.config.motion_init.velocity_prior_sigma_mps);
        sigmas.roll_pitch_rad = std::max(m->tilt_sigma_deg * M_PI / 180.0, s.config.motion_init.tilt_prior_sigma_rad);
        sigmas.gyro_bias_radps = s.config.init_gyro_bias_sigma;
      }
    }
    if (!init) {
      FrameEstimate e;
      e.stamp_ns = stamp_ns;
      e.status = s.idle_status;
      e.init_timed_out = 1e-9 * static_cast<double>(stamp_ns - s.first_frame_ns) > s.config.init_timeout_s;
      return finish(e);
    }
    s.rest_frames.clear();
    start_window(s, stamp_ns, *init, sigmas, features);
    FrameEstimate e = make_estimate(s, *s.frames.back(), EstimatorStatus::kTracking);
    s.local_map = LocalMapEstimate{stamp_ns, e.T_LB, e.T_WL, {}};
    return finish(e);
  }

  // The previous newest frame did not become a keyframe: drop it and its observations (paper Sec. III-B).
  if (!s.frames.back()->keyframe) s.frames.pop_back();
  const WindowFrame& kf = *s.frames.back();
  auto cur = std::make_unique<WindowFrame>();
  cur->id = s.next_frame_id++;
  cur->stamp_ns = stamp_ns;
  const std::vector<ImuSample> samples = covering(s.imu, kf.stamp_ns, stamp_ns);
  cur->imu_from_prev = std::make_shared<Preintegration>(preintegration_config(s.config), frame_state(kf).bias, samples,
                                                        kf.stamp_ns, stamp_ns);
  predict(kf, *cur->imu_from_prev, s.config.gravity_mps2, *cur);
  for (const auto& b : features) cur->bearings[b.id] = b.f_C;
  cur->keyframe = is_keyframe(s, kf, *cur);
  cur->stationary = is_stationary(s, kf, *cur);
  s.frames.push_back(std::move(cur));

  triangulate_new_landmarks(s);
  if (!window_finite(s)) {
    const WindowFrame& shown = window_finite_frame(*s.frames.back()) ? *s.frames.back() : kf;
    FrameEstimate e = make_estimate(s, shown, EstimatorStatus::kReinitializing);
    e.stamp_ns = stamp_ns;
    reset(s);
    return finish(e);
  }
  const SolveSummary summary = solve_window(s);
  if (diverged(s, summary)) {
    FrameEstimate e = make_estimate(s, *s.frames.back(), EstimatorStatus::kReinitializing);
    reset(s);
    return finish(e);
  }
  repropagate(s);
  const WindowFrame& newest = *s.frames.back();
  FrameEstimate e = make_estimate(s, newest, EstimatorStatus::kTracking);
  if (newest.keyframe) {
    const Eigen::Isometry3d T_LB = newest.T_LB();
    std::map<std::int64_t, Eigen::Isometry3d> keyframes;
    for (const auto& f : s.frames)
      if (f->keyframe) keyframes.emplace(f->stamp_ns, f->T_LB());
    s.horizon.follow_window(keyframes);
    s.local_map = LocalMapEstimate{newest.stamp_ns, T_LB, e.T_WL,
                                   s.horizon.update(newest.stamp_ns, T_LB.translation(), window_landmarks(s))};
    if (static_cast<int>(s.frames.size()) > s.config.window_keyframes) marginalize_oldest(s);
  }
  return finish(e);
}

}  // namespace twinslam::estimator
