// The window's world alignment and its queries: set_world_alignment (re-alignment marginalizes the old T_WL out of
// the prior), marginal covariances from the linearized term list, the window's stamps.
#include <algorithm>

#include <Eigen/Eigenvalues>
#include <ceres/cost_function.h>

#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"

namespace twinslam::estimator {

void SlidingWindowEstimator::set_world_alignment(const Eigen::Isometry3d& T_WL, const WorldAlignmentSigmas& sigmas) {
  sigmas.validate();
  WindowState& s = *s_;
  double* block = s.T_WL.data();
  if (s.prior && std::find(s.prior->parameter_blocks().begin(), s.prior->parameter_blocks().end(), block) !=
                     s.prior->parameter_blocks().end()) {
    // Integrate the old T_WL out of the prior: what the window knew about it is forgotten, the rest is kept.
    if (s.prior->parameter_blocks().size() == 1) {
      s.prior.reset();
    } else {
      Marginalizer m(s.config.marginalization);
      m.add_factor(s.prior.get(), nullptr, s.prior->parameter_blocks());
      m.marginalize_block(block);
      s.prior = m.marginalize();
    }
  }
  set_world_alignment_block(T_WL, block);
  s.world_prior = make_term(TermKind::kWorldPrior, "world alignment prior",
                            std::unique_ptr<ceres::CostFunction>(new_world_alignment_prior(T_WL, sigmas)), nullptr,
                            {block});
  s.world_aligned = true;
}

Eigen::Isometry3d SlidingWindowEstimator::world_alignment() const { return world_alignment_pose(s_->T_WL.data()); }
bool SlidingWindowEstimator::world_aligned() const { return s_->world_aligned; }

namespace {

// The joint block of `blocks` (with their tangent sizes) in the pseudo-inverse of the window's information (all
// terms, linearized at the current estimate); directions without information (none in a well-posed window) get zero
// instead of infinity. nullopt if a block is in no term.
std::optional<Eigen::MatrixXd> marginal_covariance(WindowState& s, const std::vector<std::pair<const double*, int>>& blocks) {
  Marginalizer m(s.config.marginalization);
  const std::vector<ResidualTerm> terms = build_window_terms(s);  // owns the costs the marginalizer evaluates
  for (const auto& t : terms) m.add_factor(t.cost.get(), t.loss.get(), t.blocks);
  const DenseLinearization lin = m.linearize();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (lin.H + lin.H.transpose()));
  const double eps = s.config.marginalization.min_eigenvalue;
  const Eigen::VectorXd inv = es.eigenvalues().unaryExpr([eps](double l) { return l > eps ? 1.0 / l : 0.0; });
  int rows = 0;
  for (const auto& b : blocks) rows += b.second;
  Eigen::MatrixXd V(rows, es.eigenvectors().cols());
  int r = 0;
  for (const auto& [block, tangent] : blocks) {
    const int offset = lin.offset_of(block);
    if (offset < 0) return std::nullopt;
    V.middleRows(r, tangent) = es.eigenvectors().middleRows(offset, tangent);
    r += tangent;
  }
  return Eigen::MatrixXd(V * inv.asDiagonal() * V.transpose());
}

const WindowFrame* frame_at(const WindowState& s, std::int64_t stamp_ns) {
  for (const auto& f : s.frames) {
    if (f->stamp_ns == stamp_ns) return f.get();
  }
  return nullptr;
}

}  // namespace

std::optional<Eigen::Matrix<double, 6, 6>> SlidingWindowEstimator::pose_covariance(std::int64_t stamp_ns) const {
  const WindowFrame* f = frame_at(*s_, stamp_ns);
  if (f == nullptr) return std::nullopt;
  const auto cov = marginal_covariance(*s_, {{f->pose.data(), kPoseTangentSize}});
  if (!cov) return std::nullopt;
  return Eigen::Matrix<double, 6, 6>(*cov);
}

std::optional<Eigen::Matrix<double, 6, 6>> SlidingWindowEstimator::pose_covariance_world(std::int64_t stamp_ns) const {
  const WindowFrame* f = frame_at(*s_, stamp_ns);
  if (f == nullptr) return std::nullopt;
  if (!s_->world_aligned) return pose_covariance(stamp_ns);
  const auto joint = marginal_covariance(*s_, {{f->pose.data(), kPoseTangentSize}, {s_->T_WL.data(), kWorldAlignmentSize}});
  if (!joint) return std::nullopt;
  // First order of T_WB = T_WL T_LB in [dp_L, dtheta_B, dp_WL, dyaw_WL]:
  //   dp_W = Rz dp_L + dp_WL + (e_z x Rz p_L) dyaw,   dtheta_B' = dtheta_B + R_WB^T e_z dyaw.
  const Eigen::Isometry3d T_WL = world_alignment_pose(s_->T_WL.data());
  const Eigen::Isometry3d T_LB = f->T_LB();
  const Eigen::Matrix3d Rz = T_WL.linear();
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 6, 10> J = Eigen::Matrix<double, 6, 10>::Zero();
  J.block<3, 3>(0, 0) = Rz;
  J.block<3, 3>(0, 6).setIdentity();
  J.block<3, 1>(0, 9) = e_z.cross(Rz * T_LB.translation());
  J.block<3, 3>(3, 3).setIdentity();
  J.block<3, 1>(3, 9) = (Rz * T_LB.linear()).transpose() * e_z;
  return Eigen::Matrix<double, 6, 6>(J * *joint * J.transpose());
}

std::optional<Eigen::Matrix4d> SlidingWindowEstimator::world_alignment_covariance() const {
  if (s_->frames.empty() || !s_->world_aligned) return std::nullopt;
  const auto cov = marginal_covariance(*s_, {{s_->T_WL.data(), kWorldAlignmentSize}});
  if (!cov) return std::nullopt;
  return Eigen::Matrix4d(*cov);
}

std::vector<std::int64_t> SlidingWindowEstimator::window_stamps() const {
  std::vector<std::int64_t> out;
  for (const auto& f : s_->frames) out.push_back(f->stamp_ns);
  return out;
}

}  // namespace twinslam::estimator
