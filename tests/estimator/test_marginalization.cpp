// Marginalization: the prior equals the dense Schur complement of the Hessian; solving after marginalization gives the
// full solution (linear Gaussian case); robust losses; prior Jacobians on pose blocks.
#include <memory>
#include <random>
#include <vector>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/marginalization.hpp"
#include "twinslam/geometry/quaternion.hpp"
#include "vision_test_utils.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

// r = sum_k A_k x_k - b on Euclidean blocks.
class LinearFactor final : public ceres::CostFunction {
 public:
  LinearFactor(std::vector<Eigen::MatrixXd> A, Eigen::VectorXd b) : A_(std::move(A)), b_(std::move(b)) {
    set_num_residuals(static_cast<int>(b_.size()));
    for (const auto& a : A_) mutable_parameter_block_sizes()->push_back(static_cast<int>(a.cols()));
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, b_.size());
    r = -b_;
    for (std::size_t k = 0; k < A_.size(); ++k) {
      r += A_[k] * Eigen::Map<const Eigen::VectorXd>(x[k], A_[k].cols());
      if (jacobians != nullptr && jacobians[k] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[k], A_[k].rows(),
                                                                                           A_[k].cols()) = A_[k];
      }
    }
    return true;
  }
  const std::vector<Eigen::MatrixXd>& A() const { return A_; }
  const Eigen::VectorXd& b() const { return b_; }

 private:
  std::vector<Eigen::MatrixXd> A_;
  Eigen::VectorXd b_;
};

// Five Euclidean blocks x0..x4 (sizes 3, 2, 3, 4, 1) and seven random linear factors; x0 and x1 are marginalized.
// The connected factors have enough rows (20 for 12 unknowns) that the prior has full rank and is well conditioned:
// directions with information below MarginalizationConfig::min_eigenvalue would (by design) be dropped.
struct LinearProblem {
  std::vector<Eigen::VectorXd> x{Eigen::VectorXd(3), Eigen::VectorXd(2), Eigen::VectorXd(3), Eigen::VectorXd(4),
                                 Eigen::VectorXd(1)};
  std::vector<int> offset{0, 3, 5, 8, 12};
  static constexpr int kTotal = 13, kMarginalized = 5;
  struct Entry {
    std::unique_ptr<LinearFactor> factor;
    std::vector<int> blocks;
    bool connected;  // touches x0 or x1
  };
  std::vector<Entry> factors;

  explicit LinearProblem(unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    auto random = [&](int r, int c) -> Eigen::MatrixXd { return Eigen::MatrixXd(r, c).unaryExpr([&](double) { return n(rng); }); };
    for (auto& v : x) v = random(static_cast<int>(v.size()), 1);
    const std::vector<std::pair<std::vector<int>, int>> layout{
        {{0}, 5}, {{0, 1, 2}, 8}, {{1, 3}, 7}, {{2, 3, 4}, 6}, {{4}, 1}, {{2}, 3}, {{3, 4}, 5}};
    for (const auto& [blocks, rows] : layout) {
      std::vector<Eigen::MatrixXd> A;
      for (int b : blocks) A.push_back(random(rows, static_cast<int>(x[b].size())));
      const bool connected = blocks.front() <= 1;
      factors.push_back({std::make_unique<LinearFactor>(A, random(rows, 1)), blocks, connected});
    }
  }
  std::vector<double*> pointers(const std::vector<int>& blocks) {
    std::vector<double*> p;
    for (int b : blocks) p.push_back(x[b].data());
    return p;
  }
  // Dense H and g at the current x over all 13 coordinates, of the connected factors, the others, or all.
  void dense(int which, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
    H = Eigen::MatrixXd::Zero(kTotal, kTotal);
    g = Eigen::VectorXd::Zero(kTotal);
    for (auto& f : factors) {
      if ((which == 0 && !f.connected) || (which == 1 && f.connected)) continue;
      Eigen::MatrixXd J = Eigen::MatrixXd::Zero(f.factor->b().size(), kTotal);
      for (std::size_t k = 0; k < f.blocks.size(); ++k) {
        J.middleCols(offset[f.blocks[k]], x[f.blocks[k]].size()) = f.factor->A()[k];
      }
      Eigen::VectorXd r(f.factor->b().size());
      const auto p = pointers(f.blocks);
      f.factor->Evaluate(p.data(), r.data(), nullptr);
      H += J.transpose() * J;
      g += J.transpose() * r;
    }
  }
  std::unique_ptr<est::MarginalizationPrior> marginalize() {
    est::Marginalizer marginalizer;
    for (auto& f : factors) {
      if (f.connected) marginalizer.add_factor(f.factor.get(), nullptr, pointers(f.blocks));
    }
    marginalizer.marginalize_block(x[0].data());
    marginalizer.marginalize_block(x[1].data());
    return marginalizer.marginalize();
  }
};

// The prior's H and g (over its own blocks) scattered into the 13 coordinates of LinearProblem.
void scatter_prior(LinearProblem& p, const est::MarginalizationPrior& prior, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
  std::vector<int> cols;
  for (double* b : prior.parameter_blocks()) {
    for (int blk = 0; blk < 5; ++blk) {
      if (p.x[blk].data() == b) {
        for (int i = 0; i < p.x[blk].size(); ++i) cols.push_back(p.offset[blk] + i);
      }
    }
  }
  ASSERT_EQ(static_cast<int>(cols.size()), prior.tangent_size());
  const Eigen::MatrixXd Hp = prior.hessian();
  const Eigen::VectorXd gp = prior.gradient();
  for (std::size_t i = 0; i < cols.size(); ++i) {
    g(cols[i]) += gp(static_cast<int>(i));
    for (std::size_t j = 0; j < cols.size(); ++j) H(cols[i], cols[j]) += Hp(static_cast<int>(i), static_cast<int>(j));
  }
}

// x0, x1 in R^2, a relative factor r = x1 - x0 - d and an absolute one on x0's first coordinate, 2 (x0[0] - c):
// marginalizing x0 leaves x1's second coordinate without information (a gauge direction).
struct GaugeProblem {
  Eigen::VectorXd x0 = Eigen::Vector2d(0.3, -1.0), x1 = Eigen::Vector2d(1.1, 2.0);
  const LinearFactor relative{{-Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(2, 2)},
                              Eigen::Vector2d(0.5, 0.5)};
  const LinearFactor absolute{{(Eigen::MatrixXd(1, 2) << 2.0, 0.0).finished()}, Eigen::VectorXd::Constant(1, 0.2)};
  // Both factors added and x0 marked.
  void fill(est::Marginalizer& m) {
    m.add_factor(&relative, nullptr, {x0.data(), x1.data()});
    m.add_factor(&absolute, nullptr, {x0.data()});
    m.marginalize_block(x0.data());
  }
};

}  // namespace

TEST(Marginalization, PriorEqualsTheDenseSchurComplementOfTheHessian) {
  for (unsigned seed : {41u, 42u, 43u}) {
    LinearProblem p(seed);
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    p.dense(2, H, g);
    const int m = LinearProblem::kMarginalized, n = LinearProblem::kTotal - m;
    const Eigen::MatrixXd Hmm_inv = H.topLeftCorner(m, m).inverse();
    const Eigen::MatrixXd schur = H.bottomRightCorner(n, n) - H.bottomLeftCorner(n, m) * Hmm_inv * H.topRightCorner(m, n);
    const Eigen::VectorXd g_schur = g.tail(n) - H.bottomLeftCorner(n, m) * Hmm_inv * g.head(m);

    const auto prior = p.marginalize();
    ASSERT_EQ(prior->parameter_blocks().size(), 2u);
 // x2 and x3: the blocks the connected factors share
    // Prior + the factors that were not connected = the Schur complement of the whole problem.
    Eigen::MatrixXd H_after;
    Eigen::VectorXd g_after;
    p.dense(1, H_after, g_after);
    scatter_prior(p, *prior, H_after, g_after);
    EXPECT_LT((H_after.bottomRightCorner(n, n) - schur).cwiseAbs().maxCoeff(), 1e-9 * schur.cwiseAbs().maxCoeff());
    EXPECT_LT((g_after.tail(n) - g_schur).cwiseAbs().maxCoeff(), 1e-9 * g_schur.cwiseAbs().maxCoeff()) << "seed " << seed;
    // Nothing refers to the marginalized blocks any more.
    EXPECT_EQ(H_after.topRows(m).cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(Marginalization, SolvingAfterMarginalizationGivesTheFullSolution) {
  for (unsigned seed : {44u, 45u}) {
    LinearProblem p(seed);
    const std::vector<Eigen::VectorXd> start = p.x;
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.function_tolerance = 0.0;
    options.gradient_tolerance = 1e-14;
    options.parameter_tolerance = 1e-14;
    options.max_num_iterations = 100;
    ceres::Solver::Summary summary;
    {
      ceres::Problem::Options po;
      po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
      ceres::Problem full(po);
      for (auto& f : p.factors) full.AddResidualBlock(f.factor.get(), nullptr, p.pointers(f.blocks));
      ceres::Solve(options, &full, &summary);
      ASSERT_TRUE(summary.IsSolutionUsable());
    }
    const std::vector<Eigen::VectorXd> full_solution = p.x;

    // Linearize anywhere (here the start): the problem is linear, so the prior is exact.
    p.x = start;
    const auto prior = p.marginalize();
    ceres::Problem::Options po;
    po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem reduced(po);
    reduced.AddResidualBlock(prior.get(), nullptr, prior->parameter_blocks());
    for (auto& f : p.factors) {
      if (!f.connected) reduced.AddResidualBlock(f.factor.get(), nullptr, p.pointers(f.blocks));
    }
    ceres::Solve(options, &reduced, &summary);
    ASSERT_TRUE(summary.IsSolutionUsable());
    for (int b = 2; b < 5; ++b) {
      EXPECT_LT((p.x[b] - full_solution[b]).cwiseAbs().maxCoeff(), 1e-9) << "block " << b << " seed " << seed;
    }
    EXPECT_EQ(p.x[0], start[0]);  // the marginalized blocks are no longer optimized
  }
}

TEST(Marginalization, RobustLossScalesTheFactorAsTriggsCorrection) {
  // One quadratic prior on x0 (no loss) and a 1-row factor on (x0, x1) whose residual is 4 Huber units: in Huber's
  // linear region rho'' = 0, so the factor enters with weight rho' = 1 / |r|.
  Eigen::VectorXd x0 = Eigen::VectorXd::Ones(1), x1 = Eigen::VectorXd::Ones(1);
  const LinearFactor prior0({Eigen::MatrixXd::Constant(1, 1, 2.0)}, Eigen::VectorXd::Constant(1, 2.0));
  const LinearFactor pair({Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 3.0)},
                          Eigen::VectorXd::Constant(1, 0.0));  // r = x0 + 3 x1 = 4
  const ceres::HuberLoss huber(1.0);
  est::Marginalizer marginalizer;
  marginalizer.add_factor(&prior0, nullptr, {x0.data()});
  marginalizer.add_factor(&pair, &huber, {x0.data(), x1.data()});
  marginalizer.marginalize_block(x0.data());
  const auto prior = marginalizer.marginalize();
  const double w = 1.0 / 4.0;  // rho'(|r|^2) for Huber(1) at |r| = 4
  // H = [4 + w, 3w; 3w, 9w]; Schur on x1: 9w - 9w^2 / (4 + w). g = [2*0 + w*4, 3w*4] (prior0 residual is 0).
  const double H11 = 9 * w - 9 * w * w / (4 + w);
  const double g1 = 12 * w - 3 * w / (4 + w) * 4 * w;
  EXPECT_NEAR(prior->hessian()(0, 0), H11, 1e-12);
  EXPECT_NEAR(prior->gradient()(0), g1, 1e-12);
}

TEST(Marginalization, PriorJacobiansOnPoseBlocksMatchNumeric) {
  // A prior on [pose (7), speed_bias (9)] with random J0, r0, evaluated 0.3 rad and decimetres away from its
  // linearization point: its ambient Jacobians must match numeric ones, and along q0 Exp(theta) it is exactly linear.
  std::mt19937 rng(46);
  std::normal_distribution<double> n(0.0, 1.0);
  double pose[7], speed_bias[9];
  ts::pack_pose(ts::random_pose(rng), pose);
  for (double& v : speed_bias) v = n(rng);
  const Eigen::MatrixXd J0 = Eigen::MatrixXd(12, 15).unaryExpr([&](double) { return n(rng); });
  const Eigen::VectorXd r0 = Eigen::VectorXd(12).unaryExpr([&](double) { return n(rng); });
  const est::MarginalizationPrior prior({pose, speed_bias}, {est::BlockKind::kPose, est::BlockKind::kEuclidean}, {7, 9},
                                        J0, r0);
  Eigen::Matrix<double, 15, 1> dx;
  dx << ts::random_vector(rng, 0.2), ts::random_vector(rng, 0.3), Eigen::Matrix<double, 9, 1>::Random();
  Eigen::Map<Eigen::Vector3d>{pose} += dx.head<3>();
  Eigen::Map<Eigen::Vector4d>{pose + 3} =
      (Eigen::Map<Eigen::Quaterniond>(pose + 3) * tg::quaternion_exp(dx.segment<3>(3))).coeffs();
  Eigen::Map<Eigen::Matrix<double, 9, 1>>{speed_bias} += dx.tail<9>();

  Eigen::VectorXd r;
  const auto analytic = ts::analytic_jacobians(prior, {pose, speed_bias}, &r);
  EXPECT_LT((r - (r0 + J0 * dx)).cwiseAbs().maxCoeff(), 1e-12);
  const auto numeric = ts::numeric_jacobians(prior, {pose, speed_bias});
  for (int b = 0; b < 2; ++b) EXPECT_LT(ts::max_relative_error(analytic[b], numeric[b]), 1e-6) << "block " << b;
}

TEST(Marginalization, QuaternionLiftInvertsTheRightPerturbationJacobian) {
  std::mt19937 rng(47);
  for (int i = 0; i < 10; ++i) {
    Eigen::Quaterniond q = tg::quaternion_exp(ts::random_vector(rng, 1.0));
    q.coeffs() *= 1.3;  // also off the unit sphere
    const Eigen::Matrix3d product = tg::right_perturbation_jacobian(q) * est::quaternion_right_lift(q);
    EXPECT_LT((product - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(Marginalizer, RejectsMisuse) {
  Eigen::VectorXd x0 = Eigen::VectorXd::Ones(1), x1 = Eigen::VectorXd::Ones(1);
  const LinearFactor f({Eigen::MatrixXd::Ones(1, 1)}, Eigen::VectorXd::Zero(1));
  est::Marginalizer m;
  m.add_factor(&f, nullptr, {x0.data()});
  m.marginalize_block(x1.data());  // in no factor
  EXPECT_THROW(m.marginalize(), std::logic_error);
  est::Marginalizer only;
  only.add_factor(&f, nullptr, {x0.data()});
  only.marginalize_block(x0.data());  // nothing left to hold the prior
  EXPECT_THROW(only.marginalize(), std::logic_error);
}

TEST(Marginalization, UnconstrainedDirectionsGetNoInformation) {
  // x0, x1 in R^2. A relative factor r = x1 - x0 - d and an absolute factor on x0's first coordinate only, 2 (x0[0] - c).
  // Marginalizing x0: H_mm = diag(5, 1), H_rm = -I, H_rr = I, so H* = I - diag(1/5, 1) = diag(4/5, 0): the second
  // coordinate of x1 (a gauge direction: nothing anchors it) must get exactly no information, and no gradient.
  GaugeProblem p;
  est::Marginalizer marginalizer;
  p.fill(marginalizer);
  const auto prior = marginalizer.marginalize();
  ASSERT_NE(prior, nullptr);
  EXPECT_EQ(prior->num_residuals(), 1);
  Eigen::Matrix2d expected;
  expected << 0.8, 0.0, 0.0, 0.0;
  EXPECT_LT((prior->hessian() - expected).cwiseAbs().maxCoeff(), 1e-12);
  // g*: r_rel = x1 - x0 - d = (0.3, 2.5), r_abs = 2 (0.3) - 0.2 = 0.4; g_m = -r_rel + (2 r_abs, 0) = (0.5, -2.5),
  // g_r = r_rel; g* = g_r + diag(1/5, 1) g_m = (0.3 + 0.1, 2.5 - 2.5) = (0.4, 0).
  EXPECT_LT((prior->gradient() - Eigen::Vector2d(0.4, 0.0)).cwiseAbs().maxCoeff(), 1e-12);

  // Only the relative factor: no information at all is left, so there is no prior.
  est::Marginalizer relative_only;
  relative_only.add_factor(&p.relative, nullptr, {p.x0.data(), p.x1.data()});
  relative_only.marginalize_block(p.x0.data());
  EXPECT_EQ(relative_only.marginalize(), nullptr);
}

// Process noise on a kept block (the world alignment's random walk): the prior's covariance of that block grows by
// exactly diag(variance), every other covariance entry and the mean stay; a rank-deficient prior keeps its null space.
TEST(Marginalization, ProcessNoiseGrowsOnlyThatBlocksCovarianceAndKeepsTheMean) {
  for (unsigned seed : {46u, 47u}) {
    LinearProblem p(seed);
    const auto plain = p.marginalize();
    est::Marginalizer noisy;
    for (auto& f : p.factors) {
      if (f.connected) noisy.add_factor(f.factor.get(), nullptr, p.pointers(f.blocks));
    }
    noisy.marginalize_block(p.x[0].data());
    noisy.marginalize_block(p.x[1].data());
    const Eigen::Vector4d variance(0.5, 0.0, 2.0, 0.25);  // x3 (4 coordinates); a zero leaves that one as it was
    noisy.add_process_noise(p.x[3].data(), variance);
    const auto inflated = noisy.marginalize();
    ASSERT_NE(inflated, nullptr);
    ASSERT_EQ(plain->parameter_blocks(), inflated->parameter_blocks());  // x2 (3) then x3 (4)
    const Eigen::MatrixXd cov = plain->hessian().inverse(), cov_noisy = inflated->hessian().inverse();
    Eigen::MatrixXd expected = cov;
    expected.bottomRightCorner(4, 4) += variance.asDiagonal();
    EXPECT_LT((cov_noisy - expected).cwiseAbs().maxCoeff(), 1e-8 * cov.cwiseAbs().maxCoeff()) << "seed " << seed;
    // The prior's minimum (its mean offset -H^-1 g) is where it was.
    const Eigen::VectorXd mean = -cov * plain->gradient(), mean_noisy = -cov_noisy * inflated->gradient();
    EXPECT_LT((mean_noisy - mean).cwiseAbs().maxCoeff(), 1e-8 * mean.cwiseAbs().maxCoeff());
  }
  // The gauge direction of UnconstrainedDirectionsGetNoInformation stays without information under process noise on
  // the same block, and the constrained one gets 1 / (1 / 0.8 + 0.5).
  GaugeProblem g;
  est::Marginalizer m;
  g.fill(m);
  m.add_process_noise(g.x1.data(), Eigen::Vector2d(0.5, 0.5));
  const auto prior = m.marginalize();
  ASSERT_NE(prior, nullptr);
  EXPECT_NEAR(prior->hessian()(0, 0), 1.0 / (1.0 / 0.8 + 0.5), 1e-12);
  EXPECT_LT(std::abs(prior->hessian()(1, 1)) + std::abs(prior->hessian()(0, 1)), 1e-12);
  EXPECT_THROW(m.add_process_noise(g.x1.data(), Eigen::Vector2d(-1.0, 0.0)), std::invalid_argument);
}
