// The Gaussian mixture of `gnss.model: learned`: EM recovers the weights, means and covariances of a mixture the data
// were drawn from, its log-likelihood never decreases, the covariance floor holds on collapsed data, conditioning and
// sampling give the conditional moments a direct numerical integration of the joint density gives, and degenerate
// input is refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Eigenvalues>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/learn/gaussian_mixture.hpp"

namespace twinslam::sim::learn {
namespace {

GaussianComponent component(double w, Eigen::Vector2d mean, Eigen::Matrix2d cov) {
  return GaussianComponent{w, mean, cov};
}

// Draws from a 2-D mixture with the standard library only (not with the class under test).
Eigen::MatrixXd draw(const std::vector<GaussianComponent>& truth, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  Eigen::MatrixXd X(n, 2);
  for (int i = 0; i < n; ++i) {
    double r = u(rng);
    std::size_t k = 0;
    while (k + 1 < truth.size() && r > truth[k].weight) r -= truth[k++].weight;
    const Eigen::Matrix2d L = truth[k].covariance.llt().matrixL();
    X.row(i) = (truth[k].mean + L * Eigen::Vector2d(g(rng), g(rng))).transpose();
  }
  return X;
}

std::vector<GaussianComponent> two_components() {
  Eigen::Matrix2d c0, c1;
  c0 << 1.0, 0.5, 0.5, 1.0;
  c1 << 2.0, -0.3, -0.3, 0.5;
  return {component(0.3, {0, 0}, c0), component(0.7, {6, 3}, c1)};
}

TEST(GaussianMixture, EmRecoversTheWeightsMeansAndCovariancesOfATwoComponentMixture) {
  const auto truth = two_components();
  const Eigen::MatrixXd X = draw(truth, 6000, 11);
  GmmFitReport report;
  GmmFitOptions o;
  o.components = 2;
  const GaussianMixture gmm = GaussianMixture::fit(X, o, &report);
  ASSERT_EQ(gmm.components().size(), 2u);
  EXPECT_TRUE(report.converged);
  for (const GaussianComponent& t : truth) {
    const GaussianComponent* best = nullptr;
    for (const auto& c : gmm.components()) {
      if (best == nullptr || (c.mean - t.mean).norm() < (best->mean - t.mean).norm()) best = &c;
    }
    EXPECT_NEAR(best->weight, t.weight, 0.02);
    EXPECT_LT((best->mean - t.mean).norm(), 0.1);
    EXPECT_LT((best->covariance - t.covariance).cwiseAbs().maxCoeff(), 0.15);
  }
  // The fitted model explains the data at least as well as the truth does (it is the maximum-likelihood estimate).
  EXPECT_GE(gmm.mean_log_likelihood(X), GaussianMixture(truth).mean_log_likelihood(X) - 1e-9);
  EXPECT_NEAR(report.log_likelihood.back(), gmm.mean_log_likelihood(X), 1e-9);
}

TEST(GaussianMixture, TheLogLikelihoodNeverDecreases) {
  // More components than the data have, from several seeds: EM creeps for many iterations.
  const Eigen::MatrixXd X = draw(two_components(), 3000, 12);
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    GmmFitReport report;
    GmmFitOptions o;
    o.components = 6;
    o.seed = seed;
    o.tolerance = 1e-10;
    (void)GaussianMixture::fit(X, o, &report);
    ASSERT_GT(report.log_likelihood.size(), 10u);
    for (std::size_t i = 1; i < report.log_likelihood.size(); ++i) {
      EXPECT_GE(report.log_likelihood[i], report.log_likelihood[i - 1] - 1e-12) << "seed " << seed << " it " << i;
    }
  }
}

TEST(GaussianMixture, TheCovarianceFloorHoldsOnCollapsedData) {
  // Half the points exactly at one spot (a spike, like the zero range error of clean line-of-sight signals).
  Eigen::MatrixXd X = draw(two_components(), 2000, 13);
  X.topRows(1000).rowwise() = Eigen::RowVector2d(1.0, 2.0);
  GmmFitOptions o;
  o.components = 4;
  GmmFitReport report;
  const GaussianMixture gmm = GaussianMixture::fit(X, o, &report);
  for (std::size_t i = 1; i < report.log_likelihood.size(); ++i) {
    EXPECT_GE(report.log_likelihood[i], report.log_likelihood[i - 1] - 1e-12);
  }
  const Eigen::Vector2d sd = ((X.rowwise() - X.colwise().mean()).array().square().colwise().mean()).sqrt();
  for (const auto& c : gmm.components()) {
    const Eigen::Matrix2d S = sd.cwiseInverse().asDiagonal() * c.covariance * sd.cwiseInverse().asDiagonal();
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvalues().minCoeff(), o.variance_floor * 0.999);
  }
  EXPECT_TRUE(std::isfinite(gmm.log_density(Eigen::Vector2d(1.0, 2.0))));
}

TEST(GaussianMixture, ConditionalSamplingReproducesTheConditionalMeanAndStd) {
  const GaussianMixture joint(two_components());
  for (const double a : {0.0, 2.5, 5.0}) {
    // Reference: the joint density integrated numerically along y at x = a.
    double z = 0, m1 = 0, m2 = 0;
    for (double y = -20; y <= 25; y += 1e-3) {
      const double p = std::exp(joint.log_density(Eigen::Vector2d(a, y)));
      z += p;
      m1 += p * y;
      m2 += p * y * y;
    }
    const double mean = m1 / z, sd = std::sqrt(m2 / z - mean * mean);
    const GaussianMixture cond = joint.conditional(Eigen::VectorXd::Constant(1, a));
    ASSERT_EQ(cond.dimension(), 1);
    EXPECT_NEAR(cond.mean()[0], mean, 1e-6) << "a = " << a;
    EXPECT_NEAR(std::sqrt(cond.covariance()(0, 0)), sd, 1e-6) << "a = " << a;
    std::mt19937_64 rng(17);
    double s1 = 0, s2 = 0;
    const int n = 50000;
    for (int i = 0; i < n; ++i) {
      const double y = cond.sample(rng)[0];
      s1 += y;
      s2 += y * y;
    }
    const double smean = s1 / n, ssd = std::sqrt(s2 / n - smean * smean);
    EXPECT_NEAR(smean, mean, 4 * sd / std::sqrt(n) + 1e-3) << "a = " << a;
    EXPECT_NEAR(ssd / sd, 1.0, 0.02) << "a = " << a;
  }
}

TEST(GaussianMixture, DegenerateInputIsRefusedByName) {
  const auto fails_with = [](const Eigen::MatrixXd& X, int k, const std::string& what) {
    GmmFitOptions o;
    o.components = k;
    try {
      (void)GaussianMixture::fit(X, o);
      ADD_FAILURE() << "no error for " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  Eigen::MatrixXd X = draw(two_components(), 100, 14);
  fails_with(X.topRows(5), 2, "5 points for 2 components");
  Eigen::MatrixXd bad = X;
  bad(7, 1) = std::nan("");
  fails_with(bad, 2, "data row 7 is not finite");
  Eigen::MatrixXd flat = X;
  flat.col(0).setConstant(3.0);
  fails_with(flat, 2, "dimension 0 has no spread");
  EXPECT_THROW(GaussianMixture({component(0.5, {0, 0}, Eigen::Matrix2d::Identity())}), InputError);  // weights
  EXPECT_THROW(GaussianMixture({component(1.0, {0, 0}, -Eigen::Matrix2d::Identity())}), InputError);  // not SPD
  EXPECT_THROW(GaussianMixture(two_components()).conditional(Eigen::VectorXd::Constant(2, 0.0)), InputError);
}

}  // namespace
}  // namespace twinslam::sim::learn
