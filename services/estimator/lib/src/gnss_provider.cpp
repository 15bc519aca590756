#include "twinslam/estimator/gnss_provider.hpp"

#include <cmath>
#include <cstdlib>

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/rotation.h>
#include <Eigen/Cholesky>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/world_alignment.hpp"

namespace twinslam::estimator {
namespace {

// The residual of gnss_provider.hpp; pose = [p_L, q_LB (x y z w)], speed_bias = [v_L, b_g, b_a].
struct GnssPositionFactor {
  Eigen::Vector3d z_W;
  Eigen::Matrix3d S;  // square-root information, S^T S = C^-1
  double dt_s;
  Eigen::Vector3d lever_B;

  template <class T>
  bool operator()(const T* pose, const T* speed_bias, const T* T_WL, T* r) const {
    const T q_wxyz[4] = {pose[6], pose[3], pose[4], pose[5]};
    const T lever[3] = {T(lever_B.x()), T(lever_B.y()), T(lever_B.z())};
    T lever_L[3];
    ceres::QuaternionRotatePoint(q_wxyz, lever, lever_L);
    T p_L[3];
    for (int k = 0; k < 3; ++k) p_L[k] = pose[k] + speed_bias[k] * T(dt_s) + lever_L[k];
    T p_W[3];
    world_from_local(T_WL, p_L, p_W);
    T e[3];
    for (int k = 0; k < 3; ++k) e[k] = p_W[k] - T(z_W[k]);
    for (int i = 0; i < 3; ++i) r[i] = T(S(i, 0)) * e[0] + T(S(i, 1)) * e[1] + T(S(i, 2)) * e[2];
    return true;
  }
};

}  // namespace

void GnssProviderConfig::validate() const {
  if (!lever_arm_B.allFinite()) throw InputError("gnss fusion: lever_arm_B must be finite");
  if (!(huber_delta > 0.0) || !std::isfinite(huber_delta)) throw InputError("gnss fusion: huber_delta must be > 0");
  if (!(max_dt_s > 0.0) || !std::isfinite(max_dt_s)) throw InputError("gnss fusion: max_dt_s must be > 0");
}

ceres::CostFunction* new_gnss_position_factor(const Eigen::Vector3d& z_W, const Eigen::Matrix3d& cov_W, double dt_s,
                                              const Eigen::Vector3d& lever_arm_B) {
  // S = L^-1 with C = L L^T, so that S^T S = C^-1.
  const Eigen::Matrix3d L = cov_W.llt().matrixL();
  const Eigen::Matrix3d S = L.inverse();
  return new ceres::AutoDiffCostFunction<GnssPositionFactor, 3, kPoseSize, kSpeedBiasSize, kWorldAlignmentSize>(
      new GnssPositionFactor{z_W, S, dt_s, lever_arm_B});
}

GnssProvider::GnssProvider(const GnssProviderConfig& config) : config_(config) {
  config_.validate();
  loss_ = std::make_shared<ceres::HuberLoss>(config_.huber_delta);
}

void GnssProvider::add_fix(std::int64_t stamp_ns, const Eigen::Vector3d& z_W, const Eigen::Matrix3d& cov_W) {
  const Eigen::LLT<Eigen::Matrix3d> llt(cov_W);
  if (!z_W.allFinite() || !cov_W.allFinite() || llt.info() != Eigen::Success) {
    throw InputError("gnss fusion: a fix needs a finite position and a positive definite covariance");
  }
  ++counts_.received;
  fixes_[stamp_ns] = Fix{z_W, cov_W, -1, nullptr};
}

void GnssProvider::add_terms(const WindowBlocks& blocks, std::vector<ResidualTerm>& terms) {
  if (!active_ || blocks.stamps_ns.empty()) return;
  const auto max_dt_ns = static_cast<std::int64_t>(config_.max_dt_s * 1e9);
  for (auto it = fixes_.begin(); it != fixes_.end();) {
    const std::int64_t t = it->first;
    Fix& f = it->second;
    // The nearest keyframe in the window (ties: the older one).
    std::size_t best = blocks.stamps_ns.size();
    for (std::size_t k = 0; k < blocks.stamps_ns.size(); ++k) {
      if (!blocks.is_keyframe[k]) continue;
      if (best == blocks.stamps_ns.size() ||
          std::llabs(blocks.stamps_ns[k] - t) < std::llabs(blocks.stamps_ns[best] - t)) {
        best = k;
      }
    }
    const bool near = best < blocks.stamps_ns.size() && std::llabs(blocks.stamps_ns[best] - t) <= max_dt_ns;
    if (!near) {
      // Too old for any keyframe that can still come: the window's oldest keyframe is past it.
      if (t + max_dt_ns < blocks.stamps_ns.front()) {
        ++counts_.unmatched;
        it = fixes_.erase(it);
      } else {
        ++it;  // a keyframe near it may still come
      }
      continue;
    }
    if (f.attached_to != blocks.stamps_ns[best]) {
      if (f.attached_to < 0) ++counts_.attached;
      f.attached_to = blocks.stamps_ns[best];
      f.cost.reset(new_gnss_position_factor(f.z_W, f.cov_W, 1e-9 * static_cast<double>(t - f.attached_to),
                                            config_.lever_arm_B));
    }
    ResidualTerm term;
    term.kind = TermKind::kProvider;
    term.purpose = "gnss position @ " + std::to_string(t) + " ns";
    term.cost = f.cost;
    term.loss = loss_;
    term.blocks = {blocks.pose[best], blocks.speed_bias[best], blocks.T_WL};
    terms.push_back(std::move(term));
    ++it;
  }
}

void GnssProvider::keyframe_marginalized(std::int64_t stamp_ns) {
  for (auto it = fixes_.begin(); it != fixes_.end();) {
    if (it->second.attached_to == stamp_ns) {
      ++counts_.marginalized;
      it = fixes_.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace twinslam::estimator
