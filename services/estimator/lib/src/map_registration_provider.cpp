#include "twinslam/estimator/map_registration_provider.hpp"

#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/landmark.hpp"
#include "twinslam/estimator/world_alignment.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {
namespace {

// The registration of keyframe K moved to keyframe J: T_WB_J,meas = T_WB_K,meas (T^_LB_K^-1 T^_LB_J), the VIO's
// relative motion being accurate over a few seconds. Its information, for a rotation about K's position and a
// translation, becomes one about J's position: [dtheta; dp_J] = A [dtheta; dp_K], A = [I 0; -[c_J - c_K]x I], so
// H_J = A^-T H_K A^-1.
MapRegistration moved_to(const MapRegistration& m, const Eigen::Isometry3d& T_LB_K, std::int64_t stamp_J,
                         const Eigen::Isometry3d& T_LB_J, const Eigen::Isometry3d& T_WL_J) {
  const Eigen::Isometry3d T_WB_K_meas = m.measured_T_WB();
  const Eigen::Isometry3d T_WB_J_meas = T_WB_K_meas * (T_LB_K.inverse() * T_LB_J);
  MapRegistration out;
  out.keyframe_stamp_ns = stamp_J;
  out.T_WB_estimate = T_WL_J * T_LB_J;
  out.dR_W = T_WB_J_meas.linear() * out.T_WB_estimate.linear().transpose();
  out.dp_W = T_WB_J_meas.translation() - out.T_WB_estimate.translation();
  Eigen::Matrix<double, 6, 6> A_inv = Eigen::Matrix<double, 6, 6>::Identity();
  const Eigen::Vector3d d = T_WB_J_meas.translation() - T_WB_K_meas.translation();
  A_inv.block<3, 3>(3, 0) = geometry::skew(d);  // inverse of [I 0; -[d]x I]
  out.information = A_inv.transpose() * m.information * A_inv;
  return out;
}

}  // namespace

void MapRegistrationProviderConfig::validate() const {
  if (!(huber_delta > 0.0) || !std::isfinite(huber_delta)) throw InputError("map registration: huber_delta must be > 0");
  if (!(max_reattach_s >= 0.0) || !std::isfinite(max_reattach_s)) {
    throw InputError("map registration: max_reattach_s must be >= 0");
  }
}

MapRegistrationProvider::MapRegistrationProvider(const MapRegistrationProviderConfig& config)
    : config_(config), loss_(nullptr) {
  config_.validate();
  loss_ = std::make_shared<ceres::HuberLoss>(config_.huber_delta);
}

void MapRegistrationProvider::add(const MapRegistration& registration, const Eigen::Isometry3d& T_LB_estimate) {
  ++counts_.received;
  pending_.emplace(registration.keyframe_stamp_ns, Pending{registration, T_LB_estimate, nullptr, -1});
}

void MapRegistrationProvider::attach(Pending& p, const WindowBlocks& blocks) {
  for (std::size_t k = 0; k < blocks.stamps_ns.size(); ++k) {
    if (blocks.stamps_ns[k] == p.registration.keyframe_stamp_ns && blocks.is_keyframe[k]) {
      p.cost.reset(new_map_registration_factor(p.registration));
      p.attached_to = blocks.stamps_ns[k];
      ++counts_.attached;
      return;
    }
  }
  // Its keyframe is gone (or never was one): the oldest kept keyframe, if it is near enough in time.
  if (blocks.stamps_ns.empty() || p.registration.keyframe_stamp_ns > blocks.stamps_ns.front()) {
    ++counts_.unmatched;  // a stamp inside the window that is no keyframe (a dropped frame): nothing to attach to
    p.attached_to = -2;
    return;
  }
  const double gap_s = 1e-9 * static_cast<double>(blocks.stamps_ns.front() - p.registration.keyframe_stamp_ns);
  if (gap_s > config_.max_reattach_s) {
    ++counts_.unmatched;
    p.attached_to = -2;
    return;
  }
  const Eigen::Isometry3d T_LB_J = pose_from_block(blocks.pose.front());
  const Eigen::Isometry3d T_WL_J = world_alignment_pose(blocks.T_WL);
  const MapRegistration moved = moved_to(p.registration, p.T_LB_estimate, blocks.stamps_ns.front(), T_LB_J, T_WL_J);
  p.cost.reset(new_map_registration_factor(moved));
  p.attached_to = blocks.stamps_ns.front();
  ++counts_.reattached;
}

void MapRegistrationProvider::add_terms(const WindowBlocks& blocks, std::vector<ResidualTerm>& terms) {
  for (auto it = pending_.begin(); it != pending_.end();) {
    Pending& p = it->second;
    if (p.attached_to == -1) attach(p, blocks);
    if (p.attached_to == -2) {
      it = pending_.erase(it);
      continue;
    }
    for (std::size_t k = 0; k < blocks.stamps_ns.size(); ++k) {
      if (blocks.stamps_ns[k] != p.attached_to) continue;
      ResidualTerm t;
      t.kind = TermKind::kProvider;
      t.purpose = "map registration @ " + std::to_string(p.registration.keyframe_stamp_ns) + " ns";
      t.cost = p.cost;
      t.loss = loss_;
      t.blocks = {blocks.pose[k], blocks.T_WL};
      terms.push_back(std::move(t));
    }
    ++it;
  }
}

void MapRegistrationProvider::drop_all() {
  counts_.dropped += pending_.size();
  pending_.clear();
}

void MapRegistrationProvider::keyframe_marginalized(std::int64_t stamp_ns) {
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (it->second.attached_to == stamp_ns) {
      ++counts_.marginalized;
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace twinslam::estimator
