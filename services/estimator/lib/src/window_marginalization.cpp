// Sliding the window: the oldest keyframe leaves it into the marginalization prior.
#include <ceres/cost_function.h>

#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"
#include "twinslam/estimator/state_prior.hpp"

namespace twinslam::estimator {


void marginalize_oldest(WindowState& s) {
  WindowFrame& k0 = *s.frames[0];
  WindowFrame& k1 = *s.frames[1];
  const Eigen::Vector3d g_L(0, 0, -s.config.gravity_mps2);
  // 1. Schur complement of k0's state and of the inverse depths anchored in k0 (every landmark k0 sees is anchored
  // there: anchors are the first observing keyframe) over the factors touching them: the IMU factor k0 -> k1, the
  // landmarks' reprojection factors, the previous prior and the initial-state prior (VINS-Mono, Sec. VI).
  Marginalizer m(s.config.marginalization);
  ImuFactor imu(k1.imu_from_prev, g_L);
  m.add_factor(&imu, nullptr, {k0.pose.data(), k0.speed_bias.data(), k1.pose.data(), k1.speed_bias.data()});
  std::unique_ptr<ceres::CostFunction> pose_prior, sb_prior;
  if (s.first_prior_active) {
    pose_prior.reset(new_pose_prior(s.first_prior_state, s.first_prior_sigmas));
    sb_prior.reset(new_speed_bias_prior(s.first_prior_state, s.first_prior_sigmas));
    m.add_factor(pose_prior.get(), nullptr, {k0.pose.data()});
    m.add_factor(sb_prior.get(), nullptr, {k0.speed_bias.data()});
  }
  if (s.prior) m.add_factor(s.prior.get(), nullptr, s.prior->parameter_blocks());
  std::unique_ptr<ceres::CostFunction> zero_velocity;
  if (k0.stationary) {
    zero_velocity.reset(new_zero_velocity_factor(s.config.zero_velocity_sigma_mps));
    m.add_factor(zero_velocity.get(), nullptr, {k0.speed_bias.data()});
  }
  std::vector<std::unique_ptr<ReprojectionFactor>> visual;
  std::unique_ptr<ceres::LossFunction> loss(new_reprojection_loss(s.config.reprojection_noise()));
  const double sqrt_info = s.config.reprojection_noise().sqrt_information();
  for (auto& [id, lm] : s.landmarks) {
    if (lm.lm.anchor_keyframe != k0.id) continue;
    bool any = false;
    for (std::size_t k = 1; k < s.frames.size(); ++k) {
      WindowFrame& f = *s.frames[k];
      const auto b = f.bearings.find(id);
      if (b == f.bearings.end()) continue;
      visual.push_back(std::make_unique<ReprojectionFactor>(lm.lm.f_Ca, b->second, s.config.T_BC, sqrt_info));
      m.add_factor(visual.back().get(), loss.get(), {k0.pose.data(), f.pose.data(), &lm.rho});
      any = true;
    }
    if (any) m.marginalize_block(&lm.rho);
  }
  m.marginalize_block(k0.pose.data());
  m.marginalize_block(k0.speed_bias.data());
  s.prior = m.marginalize();
  s.first_prior_active = false;

  // 2. Re-anchor those landmarks in the next keyframe observing them (landmark.hpp), so their tracks keep constraining
  // the window; drop those nobody else sees. As in VINS-Mono, their later observations are then used again next to
  // the prior that already holds the earlier ones (a slight overconfidence accepted for keeping the landmarks).
  for (auto it = s.landmarks.begin(); it != s.landmarks.end();) {
    InverseDepthLandmark& lm = it->second.lm;
    bool keep = true;
    if (lm.anchor_keyframe == k0.id) {
      keep = false;
      for (std::size_t k = 1; k < s.frames.size(); ++k) {
        const WindowFrame& f = *s.frames[k];
        const auto b = f.bearings.find(lm.id);
        if (b == f.bearings.end() || !f.keyframe) continue;
        lm.rho = it->second.rho;
        if (const auto moved = reanchor(lm, k0.T_LB(), f.T_LB(), s.config.T_BC, f.id, b->second)) {
          lm = *moved;
          it->second.rho = moved->rho;
          keep = true;
        }
        break;
      }
    }
    it = keep ? std::next(it) : s.landmarks.erase(it);
  }
  k1.imu_from_prev.reset();
  s.frames.pop_front();
}

}  // namespace twinslam::estimator
