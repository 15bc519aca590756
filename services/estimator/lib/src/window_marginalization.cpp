// Sliding the window: the oldest keyframe leaves it into the marginalization prior.
#include <algorithm>
#include <cmath>
#include <optional>

#include "twinslam/estimator/landmark.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"

namespace twinslam::estimator {
namespace {

// Re-anchors the landmarks anchored in k0 in the next keyframe observing them (landmark.hpp), so their tracks keep
// constraining the window; drops those nobody else sees. As in VINS-Mono, their later observations are then used
// again next to the prior that already holds the earlier ones (a slight overconfidence accepted for keeping them).
void reanchor_landmarks(WindowState& s, const WindowFrame& k0) {
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
        // The landmark's point is along the lens-corrected bearings; the stored bearing stays the stated one.
        InverseDepthLandmark corrected = lm;
        corrected.f_Ca = lens_bearing(s, lm.f_Ca);
        const Eigen::Vector3d f_new = lens_bearing(s, b->second);
        if (const auto moved = reanchor(corrected, k0.T_LB(), f.T_LB(), camera_T_BC(s), f.id, f_new)) {
          lm = *moved;
          lm.f_Ca = b->second.normalized();
          it->second.rho = moved->rho;
          keep = true;
        }
        break;
      }
    }
    it = keep ? std::next(it) : s.landmarks.erase(it);
  }
}

}  // namespace

MarginalizationSelection select_for_marginalization(WindowState& s, const std::vector<ResidualTerm>& terms) {
  WindowFrame& k0 = *s.frames.front();
  MarginalizationSelection sel;
  // One pass over the list. Every landmark k0 sees is anchored there (anchors are the first observing keyframe), so
  // the inverse depths to eliminate are those of the reprojection terms anchored in k0, in the list's (landmark) order.
  std::vector<double*> depths;
  for (const auto& t : terms) {
    const bool on_k0 = touches(t, k0.pose.data()) || touches(t, k0.speed_bias.data());
    // The previous prior is replaced by the new one, so it goes in whole even where it does not touch k0.
    if (on_k0 || t.kind == TermKind::kMarginalizationPrior) sel.terms.push_back(t);
    if (on_k0 && t.kind == TermKind::kReprojection && t.blocks[0] == k0.pose.data() &&
        (depths.empty() || depths.back() != t.blocks[2])) {
      depths.push_back(t.blocks[2]);
    }
  }
  sel.blocks = std::move(depths);
  sel.blocks.push_back(k0.pose.data());
  sel.blocks.push_back(k0.speed_bias.data());
  return sel;
}

namespace {

// T_WL as a random walk over the `dt_s` the prior moves forward (sliding_window_config.hpp): the alignment prior
// from set_world_alignment() goes into the marginalization prior (once), so that it ages with everything else the
// window knew of T_WL. Returns that prior's term, which must outlive m.marginalize().
std::optional<ResidualTerm> add_world_alignment_random_walk(WindowState& s, Marginalizer& m, double dt_s) {
  const double walk_m = s.config.world_alignment_random_walk_m;
  const double walk_rad = s.config.world_alignment_random_walk_deg * M_PI / 180.0;
  if (!s.world_aligned || (walk_m <= 0.0 && walk_rad <= 0.0) || !(dt_s > 0.0)) return std::nullopt;
  std::optional<ResidualTerm> retired = std::move(s.world_prior);
  s.world_prior.reset();
  if (retired) m.add_factor(retired->cost.get(), retired->loss.get(), retired->blocks);
  Eigen::VectorXd variance(kWorldAlignmentSize);  // [p_WL (m^2), yaw_WL (rad^2)]
  variance << walk_m * walk_m * dt_s, walk_m * walk_m * dt_s, walk_m * walk_m * dt_s, walk_rad * walk_rad * dt_s;
  m.add_process_noise(s.T_WL.data(), variance);
  return retired;
}

}  // namespace

void marginalize_oldest(WindowState& s) {
  WindowFrame& k0 = *s.frames[0];
  WindowFrame& k1 = *s.frames[1];
  // Schur complement of k0's blocks and the inverse depths anchored in k0 over every term acting on them (the IMU
  // term k0 -> k1, their reprojections, the priors, zero velocity, providers' terms such as a map registration or a
  // GNSS fix on k0 — their information on T_WL is kept) (VINS-Mono, Sec. VI; OKVIS).
  const std::vector<ResidualTerm> terms = build_window_terms(s);
  const MarginalizationSelection sel = select_for_marginalization(s, terms);
  Marginalizer m(s.config.marginalization);
  for (const auto& t : sel.terms) m.add_factor(t.cost.get(), t.loss.get(), t.blocks);
  for (double* b : sel.blocks) m.marginalize_block(b);
  const auto retired_world_prior =
      add_world_alignment_random_walk(s, m, 1e-9 * static_cast<double>(k1.stamp_ns - k0.stamp_ns));
  s.prior = m.marginalize();
  s.first_prior_active = false;

  reanchor_landmarks(s, k0);
  const std::int64_t stamp = k0.stamp_ns;
  k1.imu_from_prev.reset();
  s.frames.pop_front();
  for (const auto& provider : s.providers) provider->keyframe_marginalized(stamp);
}

}  // namespace twinslam::estimator
