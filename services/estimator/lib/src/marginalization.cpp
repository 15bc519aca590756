// Marginalizer: linearize the connected factors, Schur-complement the marginalized blocks, factor the result.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <Eigen/Eigenvalues>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/marginalization.hpp"

namespace twinslam::estimator {

void MarginalizationConfig::validate() const {
  if (!(min_eigenvalue > 0.0) || !std::isfinite(min_eigenvalue)) {
    throw InputError("MarginalizationConfig: min_eigenvalue must be > 0");
  }
}

Marginalizer::Marginalizer(const MarginalizationConfig& config) : config_(config) { config_.validate(); }

void Marginalizer::add_factor(const ceres::CostFunction* cost, const ceres::LossFunction* loss,
                              std::vector<double*> blocks) {
  if (cost == nullptr || blocks.size() != cost->parameter_block_sizes().size()) {
    throw std::logic_error("Marginalizer::add_factor: null cost or wrong number of blocks");
  }
  factors_.push_back({cost, loss, std::move(blocks)});
}

void Marginalizer::marginalize_block(double* block) {
  if (std::find(marginalized_.begin(), marginalized_.end(), block) == marginalized_.end()) {
    marginalized_.push_back(block);
  }
}

std::vector<ceres::ResidualBlockId> Marginalizer::add_connected(const ceres::Problem& problem,
                                                                const std::vector<double*>& blocks) {
  std::vector<ceres::ResidualBlockId> connected;
  for (double* block : blocks) {
    marginalize_block(block);
    std::vector<ceres::ResidualBlockId> ids;
    problem.GetResidualBlocksForParameterBlock(block, &ids);
    for (const auto id : ids) {
      if (std::find(connected.begin(), connected.end(), id) != connected.end()) continue;  // shared by two blocks
      std::vector<double*> params;
      problem.GetParameterBlocksForResidualBlock(id, &params);
      add_factor(problem.GetCostFunctionForResidualBlock(id), problem.GetLossFunctionForResidualBlock(id),
                 std::move(params));
      connected.push_back(id);
    }
  }
  return connected;
}

void Marginalizer::set_block_kind(double* block, BlockKind kind) { kinds_[block] = kind; }

void Marginalizer::add_process_noise(double* block, const Eigen::VectorXd& variance) {
  if (!variance.allFinite() || (variance.array() < 0.0).any()) {
    throw std::invalid_argument("Marginalizer: process noise variances must be finite and >= 0");
  }
  process_noise_.emplace_back(block, variance);
}

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

using BlockInfo = Marginalizer::BlockInfo;

// Triggs' correction of a robustified residual block (see the header): afterwards |r|^2 / 2 and J^T J, J^T r match the
// loss to second order (first order where rho'' <= 0, as ceres::Corrector).
void apply_loss(const ceres::LossFunction* loss, Eigen::VectorXd& r, Eigen::MatrixXd& J) {
  if (loss == nullptr) return;
  const double sq_norm = r.squaredNorm();
  double rho[3];
  loss->Evaluate(sq_norm, rho);
  const double sqrt_rho1 = std::sqrt(std::max(rho[1], 0.0));
  double alpha = 0.0;
  if (sq_norm > 0.0 && rho[2] > 0.0) alpha = 1.0 - std::sqrt(1.0 + 2.0 * sq_norm * rho[2] / rho[1]);
  if (sq_norm > 0.0 && alpha != 0.0) J -= (alpha / sq_norm) * r * (r.transpose() * J);
  J *= sqrt_rho1;
  r *= sqrt_rho1 / (1.0 - alpha);
}

// Pseudo-inverse of a symmetric positive semi-definite matrix, zeroing eigenvalues <= eps.
Eigen::MatrixXd psd_pseudo_inverse(const Eigen::MatrixXd& A, double eps) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
  const Eigen::VectorXd inv = es.eigenvalues().unaryExpr([eps](double l) { return l > eps ? 1.0 / l : 0.0; });
  return es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
}

}  // namespace

int DenseLinearization::offset_of(const double* block) const {
  const auto it = std::find(blocks.begin(), blocks.end(), block);
  return it == blocks.end() ? -1 : offsets[static_cast<std::size_t>(it - blocks.begin())];
}

namespace {

// Ambient -> tangent Jacobians of one factor, stacked over its blocks.
Eigen::MatrixXd tangent_jacobian(const std::vector<RowMajor>& ambient, const std::vector<double*>& blocks,
                                 const std::unordered_map<double*, BlockInfo>& info, int rows) {
  int width = 0;
  for (double* b : blocks) width += info.at(b).tangent;
  Eigen::MatrixXd J(rows, width);
  int col = 0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const BlockInfo& bi = info.at(blocks[k]);
    if (bi.kind == BlockKind::kPose) {
      const Eigen::Quaterniond q(Eigen::Map<const Eigen::Quaterniond>(blocks[k] + 3));
      J.middleCols(col, 3) = ambient[k].leftCols(3);
      J.middleCols(col + 3, 3) = ambient[k].rightCols(4) * quaternion_right_lift(q);
    } else {
      J.middleCols(col, bi.size) = ambient[k];
    }
    col += bi.tangent;
  }
  return J;
}

}  // namespace

std::unordered_map<double*, Marginalizer::BlockInfo> Marginalizer::layout(DenseLinearization& lin) const {
  // Block layout: marginalized blocks first, then the kept blocks in order of first appearance.
  std::unordered_map<double*, BlockInfo> info;
  std::vector<double*> kept;
  for (const auto& f : factors_) {
    for (std::size_t k = 0; k < f.blocks.size(); ++k) {
      double* b = f.blocks[k];
      const int size = f.cost->parameter_block_sizes()[k];
      auto [it, inserted] = info.try_emplace(b);
      if (!inserted) {
        if (it->second.size != size) throw std::logic_error("Marginalizer: one block with two sizes");
        continue;
      }
      BlockInfo& bi = it->second;
      bi.size = size;
      const auto kind = kinds_.find(b);
      bi.kind = kind != kinds_.end() ? kind->second : (size == kPoseSize ? BlockKind::kPose : BlockKind::kEuclidean);
      bi.tangent = bi.kind == BlockKind::kPose ? kPoseTangentSize : size;
      bi.marginalized = std::find(marginalized_.begin(), marginalized_.end(), b) != marginalized_.end();
      if (!bi.marginalized) kept.push_back(b);
    }
  }
  std::vector<double*> order;
  for (double* b : marginalized_) {
    if (info.find(b) == info.end()) throw std::logic_error("Marginalizer: a block to marginalize is in no factor");
    order.push_back(b);
  }
  order.insert(order.end(), kept.begin(), kept.end());
  int total = 0;
  for (double* b : order) {
    BlockInfo& bi = info[b];
    bi.offset = total;
    total += bi.tangent;
    if (bi.marginalized) lin.marginalized_tangent = total;
    lin.blocks.push_back(b);
    lin.kinds.push_back(bi.kind);
    lin.sizes.push_back(bi.size);
    lin.tangents.push_back(bi.tangent);
    lin.offsets.push_back(bi.offset);
  }
  lin.H = Eigen::MatrixXd::Zero(total, total);
  lin.g = Eigen::VectorXd::Zero(total);
  return info;
}

DenseLinearization Marginalizer::linearize() const {
  DenseLinearization lin;
  const std::unordered_map<double*, BlockInfo> info = layout(lin);
  // H = sum J^T J and g = sum J^T r in the stacked tangent coordinates.
  for (const auto& f : factors_) {
    const int rows = f.cost->num_residuals();
    const std::size_t nb = f.blocks.size();
    std::vector<RowMajor> ambient(nb);
    std::vector<double*> jac_ptrs(nb);
    for (std::size_t k = 0; k < nb; ++k) {
      ambient[k].resize(rows, info.at(f.blocks[k]).size);
      jac_ptrs[k] = ambient[k].data();
    }
    Eigen::VectorXd r(rows);
    if (!f.cost->Evaluate(f.blocks.data(), r.data(), jac_ptrs.data()) || !r.allFinite()) {
      throw std::runtime_error("Marginalizer: a factor failed to evaluate at the linearization point");
    }
    Eigen::MatrixXd J = tangent_jacobian(ambient, f.blocks, info, rows);
    apply_loss(f.loss, r, J);
    // Scatter J^T J and J^T r into H and g by block (a block may appear once per factor).
    int ci = 0;
    for (std::size_t a = 0; a < nb; ++a) {
      const BlockInfo& A = info.at(f.blocks[a]);
      lin.g.segment(A.offset, A.tangent) += J.middleCols(ci, A.tangent).transpose() * r;
      int cj = 0;
      for (std::size_t b = 0; b < nb; ++b) {
        const BlockInfo& B = info.at(f.blocks[b]);
        lin.H.block(A.offset, B.offset, A.tangent, B.tangent) +=
            J.middleCols(ci, A.tangent).transpose() * J.middleCols(cj, B.tangent);
        cj += B.tangent;
      }
      ci += A.tangent;
    }
  }
  return lin;
}

std::unique_ptr<MarginalizationPrior> Marginalizer::marginalize() const {
  const DenseLinearization lin = linearize();
  const int m = lin.marginalized_tangent;
  const int total = static_cast<int>(lin.H.rows());
  if (lin.blocks.size() == marginalized_.size()) throw std::logic_error("Marginalizer: no block remains to carry the prior");
  const Eigen::MatrixXd& H = lin.H;
  const Eigen::VectorXd& g = lin.g;

  // Schur complement (header), then H* = V S V^T -> J0 = S^1/2 V^T, r0 = S^-1/2 V^T g*.
  const int n = total - m;
  const Eigen::MatrixXd Hmm_inv = psd_pseudo_inverse(0.5 * (H.topLeftCorner(m, m) + H.topLeftCorner(m, m).transpose()),
                                                     config_.min_eigenvalue);
  const Eigen::MatrixXd Hrm = H.bottomLeftCorner(n, m);
  Eigen::MatrixXd Hs = H.bottomRightCorner(n, n) - Hrm * Hmm_inv * Hrm.transpose();
  Hs = 0.5 * (Hs + Hs.transpose());
  Eigen::VectorXd gs = g.tail(n) - Hrm * (Hmm_inv * g.head(m));
  for (const auto& [block, variance] : process_noise_) {
    const int offset = lin.offset_of(block) - m;
    if (offset < 0) continue;  // in no factor
    const int k = static_cast<int>(variance.size());
    const auto at = std::find(lin.blocks.begin(), lin.blocks.end(), block) - lin.blocks.begin();
    if (lin.kinds[at] != BlockKind::kEuclidean || lin.tangents[at] != k) {
      throw std::logic_error("Marginalizer: process noise needs a kept Euclidean block of its size");
    }
    // Woodbury (header): Cov' = Cov + E Q E^T without inverting H, which may be rank-deficient.
    const Eigen::MatrixXd Hw = Hs.middleCols(offset, k);
    const Eigen::MatrixXd Q = variance.asDiagonal();
    const Eigen::MatrixXd K = (Eigen::MatrixXd::Identity(k, k) + Q * Hw.middleRows(offset, k)).lu().solve(Q);
    gs -= Hw * (K * gs.segment(offset, k));
    Hs -= Hw * K * Hw.transpose();
    Hs = 0.5 * (Hs + Hs.transpose());
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Hs);
  std::vector<int> keep;
  for (int i = 0; i < n; ++i) {
    if (es.eigenvalues()(i) > config_.min_eigenvalue) keep.push_back(i);
  }
  const int rank = static_cast<int>(keep.size());
  if (rank == 0) return nullptr;
  Eigen::MatrixXd J0(rank, n);
  Eigen::VectorXd r0(rank);
  for (int k = 0; k < rank; ++k) {
    const double s = std::sqrt(es.eigenvalues()(keep[k]));
    const auto v = es.eigenvectors().col(keep[k]);
    J0.row(k) = s * v.transpose();
    r0(k) = v.dot(gs) / s;
  }

  const std::size_t nm = marginalized_.size();
  std::vector<double*> kept(lin.blocks.begin() + static_cast<long>(nm), lin.blocks.end());
  std::vector<BlockKind> kinds(lin.kinds.begin() + static_cast<long>(nm), lin.kinds.end());
  std::vector<int> sizes(lin.sizes.begin() + static_cast<long>(nm), lin.sizes.end());
  return std::make_unique<MarginalizationPrior>(kept, std::move(kinds), std::move(sizes), std::move(J0),
                                                std::move(r0));
}

}  // namespace twinslam::estimator
