// The window's Ceres problem: building it from the window state, solving with bounded iterations and time, outlier
// removal by reprojection error; and the triangulation of new landmarks.
#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include <ceres/ceres.h>

#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"
#include "twinslam/estimator/state_prior.hpp"
#include "twinslam/estimator/triangulation.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

WindowFrame* find_frame(WindowState& s, std::int64_t id) {
  for (auto& f : s.frames) {
    if (f->id == id) return f.get();
  }
  return nullptr;
}

// One visual residual of the problem, kept to check it after the solve.
struct VisualTerm {
  std::int64_t landmark;
  WindowFrame* anchor;
  WindowFrame* frame;
  std::unique_ptr<ReprojectionFactor> factor;
};

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
      c.obs.push_back({f->T_LB(), it->second});
    }
    if (c.anchor != nullptr && static_cast<int>(c.obs.size()) >= s.config.min_observations) {
      candidates.push_back(std::move(c));
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.obs.size() != b.obs.size() ? a.obs.size() > b.obs.size() : a.id < b.id;
  });
  for (const Candidate& c : candidates) {
    const TriangulationResult r = triangulate(tc, c.obs, s.config.T_BC, 0);
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
  std::unique_ptr<ceres::LossFunction> loss(new_reprojection_loss(c.reprojection_noise()));
  std::vector<std::unique_ptr<ceres::CostFunction>> owned;
  const Eigen::Vector3d g_L(0, 0, -c.gravity_mps2);

  WindowBlocks blocks;
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    WindowFrame& f = *s.frames[k];
    problem.AddParameterBlock(f.pose.data(), kPoseSize, manifold.get());
    problem.AddParameterBlock(f.speed_bias.data(), kSpeedBiasSize);
    if (k > 0 && f.imu_from_prev) {
      WindowFrame& p = *s.frames[k - 1];
      owned.emplace_back(new ImuFactor(f.imu_from_prev, g_L));
      problem.AddResidualBlock(owned.back().get(), nullptr, p.pose.data(), p.speed_bias.data(), f.pose.data(),
                               f.speed_bias.data());
    }
    if (f.stationary) {
      owned.emplace_back(new_zero_velocity_factor(c.zero_velocity_sigma_mps));
      problem.AddResidualBlock(owned.back().get(), nullptr, f.speed_bias.data());
    }
    blocks.stamps_ns.push_back(f.stamp_ns);
    blocks.pose.push_back(f.pose.data());
    blocks.speed_bias.push_back(f.speed_bias.data());
    blocks.is_keyframe.push_back(f.keyframe);
  }
  if (s.first_prior_active) {
    WindowFrame& f0 = *s.frames.front();
    owned.emplace_back(new_pose_prior(s.first_prior_state, s.first_prior_sigmas));
    problem.AddResidualBlock(owned.back().get(), nullptr, f0.pose.data());
    owned.emplace_back(new_speed_bias_prior(s.first_prior_state, s.first_prior_sigmas));
    problem.AddResidualBlock(owned.back().get(), nullptr, f0.speed_bias.data());
  }
  if (s.prior) problem.AddResidualBlock(s.prior.get(), nullptr, s.prior->parameter_blocks());

  std::vector<VisualTerm> terms;
  const double sqrt_info = c.reprojection_noise().sqrt_information();
  for (auto& [id, lm] : s.landmarks) {
    WindowFrame* anchor = find_frame(s, lm.lm.anchor_keyframe);
    if (anchor == nullptr) continue;  // cannot happen: marginalization re-anchors first
    for (auto& f : s.frames) {
      if (f.get() == anchor) continue;
      const auto it = f->bearings.find(id);
      if (it == f->bearings.end()) continue;
      auto factor = std::make_unique<ReprojectionFactor>(lm.lm.f_Ca, it->second, c.T_BC, sqrt_info);
      problem.AddResidualBlock(factor.get(), loss.get(), anchor->pose.data(), f->pose.data(), &lm.rho);
      terms.push_back({id, anchor, f.get(), std::move(factor)});
    }
    if (problem.HasParameterBlock(&lm.rho)) problem.SetParameterLowerBound(&lm.rho, 0, 1e-6);
  }
  for (const auto& provider : s.providers) provider->add_factors(problem, blocks);

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
  for (const auto& t : terms) {
    const WindowLandmark& lm = s.landmarks.at(t.landmark);
    const double err = t.factor->angular_error(t.anchor->pose.data(), t.frame->pose.data(), lm.rho) * c.focal_px;
    errors.push_back(err);
    if (err > c.outlier_threshold_px || !t.factor->in_front(t.anchor->pose.data(), t.frame->pose.data(), lm.rho)) {
      t.frame->bearings.erase(t.landmark);
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
  for (const auto& [id, lm] : s.landmarks) {
    const WindowFrame* anchor = nullptr;
    int observations = 0;
    for (const auto& f : s.frames) {
      if (f->id == lm.lm.anchor_keyframe) anchor = f.get();
      if (f->bearings.count(id) != 0) ++observations;
    }
    if (anchor == nullptr || observations < 2) continue;
    LandmarkEstimate e;
    e.id = id;
    e.p_L = point_in_local(anchor->T_LB(), s.config.T_BC, lm.lm.f_Ca, lm.rho);
    // Quality in [0, 1]: more observations (saturating at 5), more parallax (saturating at 5 deg) and a smaller
    // reprojection error each raise it; the product is small when any of them is poor.
    const double q_obs = std::min(1.0, (observations - 1) / 4.0);
    const double q_parallax = std::min(1.0, lm.parallax_deg / 5.0);
    const double q_error = std::clamp(1.0 - lm.mean_error_px / threshold, 0.0, 1.0);
    e.quality = q_obs * q_parallax * q_error;
    out.push_back(e);
  }
  return out;
}

}  // namespace twinslam::estimator
