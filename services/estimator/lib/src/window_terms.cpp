// The window's one list of residual terms (residual_term.hpp): IMU, zero-velocity, the initial and marginalization
// priors, bearing reprojections, the world-alignment prior and every provider's terms. The solve and the
// marginalization both build it here, in this order (the order of the Ceres residual blocks, kept from issue 5 so VIO
// results are unchanged).
#include <cmath>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>

#include "twinslam/estimator/camera_calibration.hpp"
#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/estimator/lens_calibration.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"
#include "twinslam/estimator/state_prior.hpp"

namespace twinslam::estimator {
namespace {

ResidualTerm term(TermKind kind, std::string purpose, ceres::CostFunction* cost, std::vector<double*> blocks) {
  return make_term(kind, std::move(purpose), std::unique_ptr<ceres::CostFunction>(cost), nullptr, std::move(blocks));
}

std::string frame_name(const WindowFrame& f) { return "frame " + std::to_string(f.id); }

void add_inertial_terms(WindowState& s, std::vector<ResidualTerm>& terms) {
  const Eigen::Vector3d g_L(0, 0, -s.config.gravity_mps2);
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    WindowFrame& f = *s.frames[k];
    if (k > 0 && f.imu_from_prev) {
      WindowFrame& p = *s.frames[k - 1];
      terms.push_back(term(TermKind::kImu, "imu " + frame_name(p) + " -> " + std::to_string(f.id),
                           new ImuFactor(f.imu_from_prev, g_L),
                           {p.pose.data(), p.speed_bias.data(), f.pose.data(), f.speed_bias.data()}));
    }
    if (f.stationary) {
      terms.push_back(term(TermKind::kZeroVelocity, "zero velocity " + frame_name(f),
                           new_zero_velocity_factor(s.config.zero_velocity_sigma_mps), {f.speed_bias.data()}));
    }
  }
}

void add_prior_terms(WindowState& s, std::vector<ResidualTerm>& terms) {
  if (s.first_prior_active) {
    WindowFrame& f0 = *s.frames.front();
    terms.push_back(term(TermKind::kInitialPrior, "initial pose " + frame_name(f0),
                         new_pose_prior(s.first_prior_state, s.first_prior_sigmas), {f0.pose.data()}));
    terms.push_back(term(TermKind::kInitialPrior, "initial speed/bias " + frame_name(f0),
                         new_speed_bias_prior(s.first_prior_state, s.first_prior_sigmas), {f0.speed_bias.data()}));
  }
  if (s.prior) {
    ResidualTerm t;
    t.kind = TermKind::kMarginalizationPrior;
    t.purpose = "marginalization prior";
    t.cost = s.prior;
    t.blocks = s.prior->parameter_blocks();
    terms.push_back(std::move(t));
  }
  if (calibrates_camera(s)) {
    terms.push_back(make_term(TermKind::kCameraPrior, "camera rotation prior",
                              new_camera_rotation_prior(s.config.camera_rotation_sigma_deg * M_PI / 180.0), nullptr,
                              {s.phi_BC.data()}));
  }
  if (lens_free(s)) {
    terms.push_back(make_term(TermKind::kCameraPrior, "lens prior", new_lens_prior(lens_sigmas(s.config)), nullptr,
                              {s.lens.data()}));
  }
}

void add_visual_terms(WindowState& s, std::vector<ResidualTerm>& terms) {
  const double sqrt_info = s.config.reprojection_noise().sqrt_information();
  const std::shared_ptr<ceres::LossFunction> loss(new_reprojection_loss(s.config.reprojection_noise()));
  const bool free_lens = lens_free(s);
  for (auto& [id, lm] : s.landmarks) {
    WindowFrame* anchor = find_frame(s, lm.lm.anchor_keyframe);
    if (anchor == nullptr) continue;  // cannot happen: marginalization re-anchors first
    for (auto& f : s.frames) {
      if (f.get() == anchor) continue;
      const auto it = f->bearings.find(id);
      if (it == f->bearings.end()) continue;
      ResidualTerm t;
      t.kind = TermKind::kReprojection;
      t.loss = loss;
      t.blocks = {anchor->pose.data(), f->pose.data(), &lm.rho};
      if (calibrates_camera(s)) {
        t.cost = std::make_shared<CameraRotationFactor>(lm.lm.f_Ca, it->second, s.config.T_BC, sqrt_info);
        t.blocks.push_back(s.phi_BC.data());
      } else if (free_lens) {
        t.cost = std::make_shared<LensCalibrationFactor>(lm.lm.f_Ca, it->second, s.config.T_BC, sqrt_info);
        t.blocks.push_back(s.lens.data());
      } else {
        // The lens held (or not estimated): the fixed factor on the bearings corrected as the window has them.
        t.cost = std::make_shared<ReprojectionFactor>(lens_bearing(s, lm.lm.f_Ca), lens_bearing(s, it->second),
                                                      s.config.T_BC, sqrt_info);
      }
      t.landmark = id;
      t.frame = f->id;
      terms.push_back(std::move(t));
    }
  }
}

}  // namespace

bool calibrates_camera(const WindowState& s) { return s.config.camera_rotation_sigma_deg > 0.0; }

bool calibrates_lens(const WindowState& s) { return s.config.estimates_lens(); }

std::array<double, kLensSize> lens_sigmas(const SlidingWindowConfig& c) {
  const double center_rad = c.lens_center_sigma_px / c.focal_px;
  return {c.lens_scale_sigma, c.lens_k1_sigma, center_rad, center_rad};
}

bool lens_excited(const WindowState& s) {
  if (s.frames.empty() || s.first_frame_ns < 0 ||
      static_cast<double>(s.frames.back()->stamp_ns - s.first_frame_ns) < s.config.lens_settle_s * 1e9) {
    return false;
  }
  // The largest angle between two frames' optical axes in L (the window holds a handful of frames).
  const Eigen::Matrix3d R_BC = camera_T_BC(s).linear();
  std::vector<Eigen::Vector3d> axes;
  for (const auto& f : s.frames) axes.push_back(f->T_LB().linear() * R_BC.col(2));
  const double min_cos = std::cos(s.config.lens_excitation_deg * M_PI / 180.0);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    for (std::size_t j = i + 1; j < axes.size(); ++j) {
      if (axes[i].dot(axes[j]) <= min_cos) return true;
    }
  }
  return s.config.lens_excitation_deg <= 0.0;
}

bool lens_free(const WindowState& s) { return calibrates_lens(s) && lens_excited(s); }

Eigen::Vector3d lens_bearing(const WindowState& s, const Eigen::Vector3d& f) {
  // A zero correction returns f itself, bit for bit: until the lens is first freed the window is the fixed-lens one.
  const bool zero = s.lens[0] == 0.0 && s.lens[1] == 0.0 && s.lens[2] == 0.0 && s.lens[3] == 0.0;
  return calibrates_lens(s) && !zero ? corrected_bearing(f, s.lens.data()) : f;
}

Eigen::Isometry3d camera_T_BC(const WindowState& s) {
  return calibrates_camera(s) ? calibrated_T_BC(s.config.T_BC, s.phi_BC.data()) : s.config.T_BC;
}

WindowFrame* find_frame(WindowState& s, std::int64_t id) {
  for (auto& f : s.frames) {
    if (f->id == id) return f.get();
  }
  return nullptr;
}

WindowBlocks window_blocks(WindowState& s) {
  WindowBlocks blocks;
  for (auto& f : s.frames) {
    blocks.stamps_ns.push_back(f->stamp_ns);
    blocks.pose.push_back(f->pose.data());
    blocks.speed_bias.push_back(f->speed_bias.data());
    blocks.is_keyframe.push_back(f->keyframe);
  }
  blocks.T_WL = s.T_WL.data();
  return blocks;
}

std::vector<ResidualTerm> build_window_terms(WindowState& s) {
  std::vector<ResidualTerm> terms;
  terms.reserve(s.frames.size() * 2 + s.landmarks.size() * s.frames.size() / 2 + 8);
  add_inertial_terms(s, terms);
  add_prior_terms(s, terms);
  add_visual_terms(s, terms);
  if (s.world_prior) terms.push_back(*s.world_prior);
  if (!s.providers.empty()) {
    const WindowBlocks blocks = window_blocks(s);
    for (const auto& provider : s.providers) provider->add_terms(blocks, terms);
  }
  return terms;
}

}  // namespace twinslam::estimator
