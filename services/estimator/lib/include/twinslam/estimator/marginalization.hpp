#pragma once
// Marginalization of sliding-window variables into a prior factor (the Schur complement of the linearized factors),
// as VINS-Mono's MarginalizationFactor (Qin et al., TRO 2018, Sec. VI, marginalization) and OKVIS
// (Leutenegger et al., IJRR 2015, marginalization section).
//
// Given the factors connected to the variables x_m to remove, linearized at the current values x0:
//   sum_f |r_f(x0 [+] dx)|^2 ~= |r(x0) + J dx|^2,   H = J^T J,   g = J^T r,
// ordered [x_m, x_r] (x_r: the other blocks those factors touch), the Gaussian over x_r after eliminating x_m is
//   H* = H_rr - H_rm H_mm^-1 H_mr,   g* = g_r - H_rm H_mm^-1 g_m
// (the Schur complement of the sliding window filter, Sibley et al., JFR 2010, and of OKVIS),
// and the prior factor is r_p(x_r) = r0 + J0 (x_r [-] x_r0) with J0^T J0 = H*, J0^T r0 = g*, obtained from the
// eigen-decomposition H* = V S V^T: J0 = S^1/2 V^T, r0 = S^-1/2 V^T g* (as VINS-Mono), keeping eigenvalues above
// MarginalizationConfig::min_eigenvalue (unconstrained directions, e.g. the gauge, get no information).
//
// Manifolds: Jacobians are taken in a tangent space, the linearization point is kept (first-estimate Jacobians):
//  - pose blocks [p_L, q_LB xyzw] (kPoseSize): dx = [p - p0, Log(q0^-1 q)], the right (body-frame) perturbation of
//    imu_state.hpp, so the factors' ambient Jacobians map to it exactly with the 4x3 lift dq/dtheta;
//  - every other block is Euclidean (speed_bias, inverse depth, ...).
// Robust losses of the marginalized factors are applied by Triggs' correction (Triggs et al., "Bundle Adjustment - A
// Modern Synthesis", 2000, robustified cost section), the same as ceres::Corrector.
#include <memory>
#include <unordered_map>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::estimator {

enum class BlockKind { kEuclidean, kPose };

struct MarginalizationConfig {
  // Eigenvalues of H_mm and H* at or below this are treated as zero [information units of the whitened residuals];
  // VINS-Mono uses the same 1e-8.
  double min_eigenvalue = 1e-8;
  void validate() const;  // throws twinslam::InputError
};

// d(q)/d(dtheta) at dtheta = 0 for q (x) Exp(dtheta), 4x3 in memory order x, y, z, w: maps the pose factors' ambient
// quaternion Jacobians to the right-perturbation tangent (geometry::right_perturbation_jacobian(q) times it is I).
Eigen::Matrix<double, 4, 3> quaternion_right_lift(const Eigen::Quaterniond& q);

// The prior on the kept blocks. Add it to the problem with its parameter_blocks(); it does not own them.
class MarginalizationPrior final : public ceres::CostFunction {
 public:
  MarginalizationPrior(std::vector<double*> blocks, std::vector<BlockKind> kinds, std::vector<int> sizes,
                       Eigen::MatrixXd J0, Eigen::VectorXd r0);

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

  const std::vector<double*>& parameter_blocks() const { return blocks_; }
  // Information and gradient in the stacked tangent coordinates of parameter_blocks(), at the linearization point.
  Eigen::MatrixXd hessian() const { return J0_.transpose() * J0_; }
  Eigen::VectorXd gradient() const { return J0_.transpose() * r0_; }
  const std::vector<Eigen::VectorXd>& linearization_point() const { return x0_; }
  int tangent_size() const { return static_cast<int>(J0_.cols()); }

 private:
  std::vector<double*> blocks_;
  std::vector<BlockKind> kinds_;
  std::vector<int> offsets_;  // tangent offset of each block
  std::vector<Eigen::VectorXd> x0_;
  Eigen::MatrixXd J0_;
  Eigen::VectorXd r0_;
};

// The factors of a Marginalizer linearized at the current block values: H = sum J^T J, g = sum J^T r in stacked tangent
// coordinates (pose blocks [dp, dtheta], translation first; others Euclidean), robust losses applied (Triggs).
// Blocks: the marginalized ones first (in marginalize_block() order), then the others in order of first appearance.
struct DenseLinearization {
  std::vector<double*> blocks;
  std::vector<BlockKind> kinds;
  std::vector<int> sizes;     // ambient
  std::vector<int> tangents;  // tangent
  std::vector<int> offsets;   // tangent offset in H
  int marginalized_tangent = 0;  // H's leading rows/columns that belong to marginalized blocks
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  int offset_of(const double* block) const;  // -1 if the block is in no factor
};

// Collects the factors connected to the blocks to marginalize and builds the prior.
// Usage per window slide: add every factor touching a marginalized block (IMU factors, reprojection factors of the
// landmarks being dropped, the previous prior), mark the blocks, call marginalize() BEFORE removing those factors from
// the ceres::Problem (they are evaluated there; pointers need not outlive the call), then remove the factors and
// blocks and add the new prior.
class Marginalizer {
 public:
  explicit Marginalizer(const MarginalizationConfig& config = {});

  void add_factor(const ceres::CostFunction* cost, const ceres::LossFunction* loss, std::vector<double*> blocks);
  void marginalize_block(double* block);
  // Marks `blocks` and adds every residual block of `problem` touching one of them (cost, loss and parameter blocks as
  // the problem holds them). Returns those residual blocks: remove them from the problem after marginalize().
  std::vector<ceres::ResidualBlockId> add_connected(const ceres::Problem& problem, const std::vector<double*>& blocks);
  // Kinds default from the size (kPoseSize -> kPose, otherwise kEuclidean); override here.
  void set_block_kind(double* block, BlockKind kind);
  // Process noise on a kept Euclidean block: the prior's covariance of `block` grows by diag(variance) (one entry per
  // coordinate, >= 0; a zero leaves that coordinate as it was), every other marginal and the mean stay (Woodbury on the
  // Schur complement: H' = H - H_w (I + Q H_ww)^-1 Q H_w^T, g' = g - H_w (I + Q H_ww)^-1 Q g_w, valid for a rank-
  // deficient H). What a slowly varying state needs, whose information would otherwise pile up in the prior forever
  // (the world alignment T_WL: sliding_window_config.hpp, world_alignment_random_walk). Ignored when the block is in no
  // factor. Throws std::invalid_argument for a negative or non-finite variance.
  void add_process_noise(double* block, const Eigen::VectorXd& variance);

  // Evaluates the factors at the current block values (see DenseLinearization). Throws like marginalize(), except
  // that here no block needs to remain (the window's full Hessian for covariances).
  DenseLinearization linearize() const;
  // Evaluates the factors at the current block values and returns the prior on the remaining blocks, or nullptr when
  // it carries no information (every direction truncated, e.g. only relative factors). Throws std::logic_error if a
  // marked block is in no factor or no block remains, std::runtime_error if a factor fails to evaluate.
  std::unique_ptr<MarginalizationPrior> marginalize() const;

  // Where a block sits in a linearization (used by linearize()'s helpers).
  struct BlockInfo {
    int size = 0;      // ambient
    int tangent = 0;   // tangent
    int offset = -1;   // in the stacked tangent vector [x_m, x_r]
    BlockKind kind = BlockKind::kEuclidean;
    bool marginalized = false;
  };

 private:
  struct Factor {
    const ceres::CostFunction* cost;
    const ceres::LossFunction* loss;
    std::vector<double*> blocks;
  };
  // Orders the blocks into `lin` (sizes H and g); returns the per-block layout the linearization scatters into.
  std::unordered_map<double*, BlockInfo> layout(DenseLinearization& lin) const;

  MarginalizationConfig config_;
  std::vector<Factor> factors_;
  std::vector<double*> marginalized_;
  std::unordered_map<double*, BlockKind> kinds_;
  std::vector<std::pair<double*, Eigen::VectorXd>> process_noise_;
};

}  // namespace twinslam::estimator
