// The window's Ceres problem: building it from the window state, solving with bounded iterations and time, outlier
// removal by reprojection error; and the triangulation of new landmarks.
#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include <ceres/ceres.h>

#include "twinslam/estimator/camera_calibration.hpp"
#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/estimator/lens_calibration.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"
#include "twinslam/estimator/state_prior.hpp"
#include "twinslam/estimator/triangulation.hpp"

namespace twinslam::estimator {
namespace {

// Reprojection error [px] of one reprojection term after the solve, and whether the point is in front of the camera,
// with the camera rotation R_BC the window estimates now (camera_T_BC(s), computed once per solve by the caller).
std::pair<double, bool> reprojection_error_px(WindowState& s, const ResidualTerm& t, const Eigen::Matrix3d& R_BC) {
  const WindowLandmark& lm = s.landmarks.at(t.landmark);
  const WindowFrame* anchor = find_frame(s, lm.lm.anchor_keyframe);
  const WindowFrame* frame = find_frame(s, t.frame);
  if (const auto* lens = dynamic_cast<const LensCalibrationFactor*>(t.cost.get())) {
    return {lens->angular_error(anchor->pose.data(), frame->pose.data(), lm.rho, s.lens.data()) * s.config.focal_px,
            lens->in_front(anchor->pose.data(), frame->pose.data(), lm.rho, s.lens.data())};
  }
  const auto* factor = dynamic_cast<const ReprojectionFactor*>(t.cost.get());
  if (factor == nullptr) factor = &static_cast<const CameraRotationFactor&>(*t.cost).reprojection();
  return {factor->angular_error(anchor->pose.data(), frame->pose.data(), lm.rho, &R_BC) * s.config.focal_px,
          factor->in_front(anchor->pose.data(), frame->pose.data(), lm.rho, &R_BC)};
}

// Largest angle [deg] between the anchor keyframe's ray to landmark `id` and another observer's, both in L.
double current_parallax_deg(const WindowState& s, const Eigen::Isometry3d& T_BC, const WindowFrame& anchor,
                            const std::vector<const WindowFrame*>& observers, std::int64_t id) {
  const Eigen::Vector3d d_a =
      (anchor.T_LB().linear() * T_BC.linear() * lens_bearing(s, anchor.bearings.at(id))).normalized();
  double cos_min = 1.0;
  for (const WindowFrame* f : observers) {
    const Eigen::Vector3d d = (f->T_LB().linear() * T_BC.linear() * lens_bearing(s, f->bearings.at(id))).normalized();
    cos_min = std::min(cos_min, d_a.dot(d));
  }
  return std::acos(std::clamp(cos_min, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

StatePriorSigmas static_init_prior_sigmas(const SlidingWindowConfig& c) {
  StatePriorSigmas p;
  p.position_m = c.init_position_sigma_m;
  p.roll_pitch_rad = c.init_roll_pitch_sigma_rad;
  p.yaw_rad = c.init_yaw_sigma_rad;
  p.velocity_mps = c.init_velocity_sigma_mps;
  p.gyro_bias_radps = c.init_gyro_bias_sigma;
  p.accel_bias_mps2 = c.init_accel_bias_sigma;
  return p;
}

void triangulate_new_landmarks(WindowState& s) {
  if (static_cast<int>(s.landmarks.size()) >= s.config.max_landmarks) return;
  TriangulationConfig tc = s.config.triangulation;
  tc.focal_px = s.config.focal_px;
  // Candidates: tracks of the newest frame that are no landmark yet, anchored in their first keyframe. Longest tracks
  // first: with a capped landmark count, each landmark then constrains the most keyframes (and sorting by id breaks
  // ties, so the choice does not depend on hash order: deterministic).
  struct Candidate {
    std::int64_t id;
    const WindowFrame* anchor;
    std::vector<BearingObservation> obs;
  };
  std::vector<Candidate> candidates;
  for (const auto& [id, f_new] : s.frames.back()->bearings) {
    if (s.landmarks.count(id) != 0) continue;
    Candidate c{id, nullptr, {}};
    for (const auto& f : s.frames) {
      const auto it = f->bearings.find(id);
      if (it == f->bearings.end()) continue;
      if (c.anchor == nullptr) {
        if (!f->keyframe) break;  // anchors must be keyframes: a non-keyframe is dropped with its observations
        c.anchor = f.get();
      }
      c.obs.push_back({f->T_LB(), lens_bearing(s, it->second)});
    }
    if (c.anchor != nullptr && static_cast<int>(c.obs.size()) >= s.config.min_observations) {
      candidates.push_back(std::move(c));
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.obs.size() != b.obs.size() ? a.obs.size() > b.obs.size() : a.id < b.id;
  });
  for (const Candidate& c : candidates) {
    const TriangulationResult r = triangulate(tc, c.obs, camera_T_BC(s), 0);
    if (!r.ok()) continue;
    WindowLandmark lm;
    lm.lm.id = c.id;
    lm.lm.anchor_keyframe = c.anchor->id;
    lm.lm.f_Ca = c.anchor->bearings.at(c.id);
    lm.lm.rho = r.rho;
    lm.rho = r.rho;
    lm.mean_error_px = r.max_error_px;
    lm.parallax_deg = r.parallax_deg;
    s.landmarks.emplace(c.id, lm);
    if (static_cast<int>(s.landmarks.size()) >= s.config.max_landmarks) return;
  }
}

SolveSummary solve_window(WindowState& s) {
  const SlidingWindowConfig& c = s.config;
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  std::unique_ptr<ceres::Manifold> manifold(new_pose_manifold());
  // Frame blocks first, in window order (the Schur ordering then matches issue 5's problem exactly).
  for (auto& f : s.frames) {
    problem.AddParameterBlock(f->pose.data(), kPoseSize, manifold.get());
    problem.AddParameterBlock(f->speed_bias.data(), kSpeedBiasSize);
  }
  const std::vector<ResidualTerm> terms = build_window_terms(s);
  add_to_problem(terms, problem);
  // The lens values configured with sigma 0 stay as stated (lens_calibration.hpp); all are held while the window
  // does not rotate the camera enough to tell them from depth (lens_excited).
  std::unique_ptr<ceres::Manifold> lens_manifold;
  if (problem.HasParameterBlock(s.lens.data())) {
    if (!lens_free(s)) {
      problem.SetParameterBlockConstant(s.lens.data());
    } else {
      lens_manifold = new_lens_manifold(lens_sigmas(c));
      if (lens_manifold) problem.SetManifold(s.lens.data(), lens_manifold.get());
    }
  }
  for (auto& [id, lm] : s.landmarks) {
    if (problem.HasParameterBlock(&lm.rho)) problem.SetParameterLowerBound(&lm.rho, 0, 1e-6);
  }
  // T_WL is in the problem only through terms acting on it: from then on T_WB is in W.
  if (problem.HasParameterBlock(s.T_WL.data())) s.world_aligned = true;

  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_SCHUR;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.max_num_iterations = c.max_solver_iterations;
  so.max_solver_time_in_seconds = c.max_solver_time_s;
  so.num_threads = 1;
  so.function_tolerance = c.solver_function_tolerance;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);

  // Outliers: observations farther than the threshold, or behind the camera, are removed from their frame (the
  // track is cut there); landmarks left with rho <= 0 are removed.
  SolveSummary out;
  std::vector<double> errors;
  std::map<std::int64_t, std::pair<double, int>> per_landmark;  // sum of errors, count
  const Eigen::Matrix3d R_BC = camera_T_BC(s).linear();
  for (const auto& t : terms) {
    if (t.kind != TermKind::kReprojection) continue;
    const auto [err, in_front] = reprojection_error_px(s, t, R_BC);
    errors.push_back(err);
    if (err > c.outlier_threshold_px || !in_front) {
      find_frame(s, t.frame)->bearings.erase(t.landmark);
      ++out.outliers_removed;
    } else {
      auto& acc = per_landmark[t.landmark];
      acc.first += err;
      acc.second += 1;
    }
  }
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    out.median_error_px = errors[errors.size() / 2];
  }
  for (auto it = s.landmarks.begin(); it != s.landmarks.end();) {
    WindowLandmark& lm = it->second;
    lm.lm.rho = lm.rho;
    const auto acc = per_landmark.find(it->first);
    lm.mean_error_px = acc == per_landmark.end() ? 0.0 : acc->second.first / acc->second.second;
    it = (!(lm.rho > 1e-5) || !std::isfinite(lm.rho)) ? s.landmarks.erase(it) : std::next(it);
  }
  return out;
}

std::vector<LandmarkEstimate> window_landmarks(const WindowState& s) {
  std::vector<LandmarkEstimate> out;
  const double threshold = s.config.outlier_threshold_px;
  const Eigen::Isometry3d T_BC = camera_T_BC(s);
  for (const auto& [id, lm] : s.landmarks) {
    const WindowFrame* anchor = nullptr;
    std::vector<const WindowFrame*> observers;
    for (const auto& f : s.frames) {
      if (f->id == lm.lm.anchor_keyframe) anchor = f.get();
      if (f->bearings.count(id) != 0) observers.push_back(f.get());
    }
    if (anchor == nullptr || observers.size() < 2) continue;
    LandmarkEstimate e;
    e.id = id;
    const Eigen::Vector3d f_Ca = lens_bearing(s, lm.lm.f_Ca);
    e.p_L = point_in_local(anchor->T_LB(), T_BC, f_Ca, lm.rho);
    // Quality in [0, 1]: more observations (saturating at 5), more parallax (saturating at 5 deg) and a smaller
    // reprojection error each raise it; the product is small when any of them is poor. The parallax is that of the
    // keyframes observing it now, not at triangulation: a landmark first triangulated from a short baseline gains
    // parallax as later keyframes see it, and its depth is then as well determined as any other's.
    const double parallax_deg = std::max(lm.parallax_deg, current_parallax_deg(s, T_BC, *anchor, observers, id));
    const double q_obs = std::min(1.0, (static_cast<double>(observers.size()) - 1.0) / 4.0);
    const double q_parallax = std::min(1.0, parallax_deg / 5.0);
    const double q_error = std::clamp(1.0 - lm.mean_error_px / threshold, 0.0, 1.0);
    e.quality = q_obs * q_parallax * q_error;
    std::vector<Eigen::Vector3d> centres;
    centres.reserve(observers.size());
    for (const WindowFrame* f : observers) centres.push_back((f->T_LB() * T_BC).translation());
    const Eigen::Isometry3d T_LCa = anchor->T_LB() * T_BC;
    e.cov_L = landmark_covariance_L(T_LCa.translation(), (T_LCa.linear() * f_Ca).normalized(), lm.rho, centres,
                                    s.config.pixel_sigma / s.config.focal_px);
    out.push_back(e);
  }
  return out;
}

}  // namespace twinslam::estimator
