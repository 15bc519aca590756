#include "twinslam/estimator/loose_gnss_fusion.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {
namespace {

double seconds(std::int64_t ns) { return 1e-9 * static_cast<double>(ns); }

// The VIO pose at `stamp_ns` between two poses (position linear, attitude slerp).
Eigen::Isometry3d interpolate(std::int64_t a_ns, const Eigen::Isometry3d& a, std::int64_t b_ns,
                              const Eigen::Isometry3d& b, std::int64_t stamp_ns) {
  const double s = b_ns == a_ns ? 0.0 : seconds(stamp_ns - a_ns) / seconds(b_ns - a_ns);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = (1.0 - s) * a.translation() + s * b.translation();
  T.linear() = Eigen::Quaterniond(a.linear()).slerp(s, Eigen::Quaterniond(b.linear())).normalized().toRotationMatrix();
  return T;
}

bool usable_covariance(const Eigen::Matrix3d& cov) {
  if (!cov.allFinite() || !cov.isApprox(cov.transpose(), 1e-9)) return false;
  return Eigen::LLT<Eigen::Matrix3d>(cov).info() == Eigen::Success;
}

}  // namespace

void LooseGnssFusionConfig::validate() const {
  const std::pair<const char*, double> positive[] = {
      {"node_interval_s", node_interval_s},       {"odometry_sigma_per_m", odometry_sigma_per_m},
      {"odometry_min_sigma_m", odometry_min_sigma_m}, {"odometry_deg_per_m", odometry_deg_per_m},
      {"odometry_min_sigma_deg", odometry_min_sigma_deg}, {"prior_sigma_m", prior_sigma_m},
      {"prior_sigma_deg", prior_sigma_deg},       {"huber_delta", huber_delta},
      {"max_pairing_dt_s", max_pairing_dt_s}};
  for (const auto& [name, v] : positive) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(std::string("loose gnss fusion: ") + name + " must be > 0");
  }
  if (window_nodes < 2) throw InputError("loose gnss fusion: window_nodes must be >= 2");
  if (max_iterations < 1) throw InputError("loose gnss fusion: max_iterations must be >= 1");
  if (!lever_arm_B.allFinite()) throw InputError("loose gnss fusion: lever_arm_B must be finite");
}

LooseGnssFusion::LooseGnssFusion(const LooseGnssFusionConfig& config) : config_(config) { config_.validate(); }

void LooseGnssFusion::start(const Eigen::Isometry3d& T_WL) {
  started_ = true;
  T_WL_ = T_WL;
  nodes_.clear();
  prior_T_WB_.reset();
  pending_.clear();
}

void LooseGnssFusion::add_fix(std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const Eigen::Matrix3d& cov_W) {
  ++counts_.fixes_in;
  if (!started_) return;  // before the alignment: the graph has no W to put it in
  if (!p_W.allFinite() || !usable_covariance(cov_W)) {
    ++counts_.fixes_unpaired;
    return;
  }
  pending_.push_back({stamp_ns, p_W, cov_W});
  pair_pending();
}

void LooseGnssFusion::add_odometry(std::int64_t stamp_ns, const Eigen::Isometry3d& T_LB) {
  if (newest_ && stamp_ns <= newest_->stamp_ns) return;
  previous_ = newest_;
  newest_ = Pose{stamp_ns, T_LB};
  if (!started_) return;
  const bool new_node =
      nodes_.empty() || seconds(stamp_ns - nodes_.back().stamp_ns) >= config_.node_interval_s - 1e-9;
  if (new_node) {
    nodes_.push_back({stamp_ns, T_LB, T_WL_ * T_LB, {}});
    ++counts_.nodes;
    if (nodes_.size() == 1) {
      prior_T_WB_ = nodes_.front().T_WB;  // the alignment's pose anchors the graph until the window is full
    } else if (nodes_.size() > static_cast<std::size_t>(config_.window_nodes)) {
      nodes_.pop_front();
      prior_T_WB_ = nodes_.front().T_WB;  // what the dropped nodes said, at the new oldest node
    }
  }
  pair_pending();
  if (new_node) solve();
}

void LooseGnssFusion::pair_pending() {
  if (!newest_) return;
  std::vector<Pending> keep;
  for (const auto& f : pending_) {
    if (f.stamp_ns > newest_->stamp_ns) {
      keep.push_back(f);  // not bracketed yet: the next VIO pose pairs it
      continue;
    }
    std::optional<Eigen::Isometry3d> T_LB;
    if (previous_ && f.stamp_ns >= previous_->stamp_ns &&
        std::min(f.stamp_ns - previous_->stamp_ns, newest_->stamp_ns - f.stamp_ns) <=
            static_cast<std::int64_t>(config_.max_pairing_dt_s * 1e9)) {
      T_LB = interpolate(previous_->stamp_ns, previous_->T_LB, newest_->stamp_ns, newest_->T_LB, f.stamp_ns);
    } else if (seconds(newest_->stamp_ns - f.stamp_ns) <= config_.max_pairing_dt_s) {
      T_LB = newest_->T_LB;
    }
    if (T_LB && !nodes_.empty()) {
      attach(f.stamp_ns, *T_LB, f.z_W, f.cov_W);
    } else {
      ++counts_.fixes_unpaired;
    }
  }
  // A VIO that stopped producing poses must not make the fixes pile up: the oldest waiting ones go, counted.
  constexpr std::size_t kMaxPending = 64;
  if (keep.size() > kMaxPending) {
    counts_.fixes_unpaired += keep.size() - kMaxPending;
    keep.erase(keep.begin(), keep.end() - kMaxPending);
  }
  pending_ = std::move(keep);
}

void LooseGnssFusion::attach(std::int64_t stamp_ns, const Eigen::Isometry3d& T_LB_fix, const Eigen::Vector3d& z_W,
                             const Eigen::Matrix3d& cov_W) {
  // The newest node at or before the fix (the first node for an older fix).
  auto node = nodes_.begin();
  for (auto it = nodes_.begin(); it != nodes_.end() && it->stamp_ns <= stamp_ns; ++it) node = it;
  node->fixes.push_back({z_W, cov_W, node->T_LB.inverse() * T_LB_fix});
  ++counts_.fixes_used;
}

void LooseGnssFusion::solve() {
  const bool any_fix = std::any_of(nodes_.begin(), nodes_.end(), [](const Node& n) { return !n.fixes.empty(); });
  if (!any_fix) return;
  solve_loose_graph(nodes_, prior_T_WB_, config_);
  ++counts_.solves;
  T_WL_ = nodes_.back().T_WB * nodes_.back().T_LB.inverse();
}

}  // namespace twinslam::estimator
