#include "twinslam/sim/learn/gaussian_mixture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "twinslam/core/error.hpp"

namespace twinslam::sim::learn {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

[[noreturn]] void fail(const std::string& what) { throw InputError("gaussian mixture: " + what); }

double log_sum_exp(const Eigen::VectorXd& v) {
  const double m = v.maxCoeff();
  if (!std::isfinite(m)) return m;
  return m + std::log((v.array() - m).exp().sum());
}

// The symmetric matrix with S's eigenvectors and its eigenvalues raised to at least `floor`.
Eigen::MatrixXd clamp_eigenvalues(const Eigen::MatrixXd& S, double floor) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (S + S.transpose()));
  const Eigen::VectorXd lambda = es.eigenvalues().cwiseMax(floor);
  Eigen::MatrixXd C = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  return 0.5 * (C + C.transpose());
}

// log N(x_i; mean, L L^T) for every column x_i of X (D x n).
Eigen::VectorXd log_gaussian_columns(const Eigen::MatrixXd& X, const Eigen::VectorXd& mean,
                                     const Eigen::MatrixXd& L) {
  const Eigen::MatrixXd Y = L.triangularView<Eigen::Lower>().solve(X.colwise() - mean);
  const double log_norm = -0.5 * static_cast<double>(X.rows()) * std::log(2 * std::numbers::pi) -
                          L.diagonal().array().log().sum();
  return (log_norm - 0.5 * Y.colwise().squaredNorm().array()).matrix().transpose();
}

// k-means++ seeding and Lloyd iterations on the columns of Z (D x n): the labels of the points.
std::vector<int> kmeans(const Eigen::MatrixXd& Z, int k, int iterations, std::mt19937_64& rng,
                        Eigen::MatrixXd* centres) {
  const Eigen::Index n = Z.cols();
  *centres = Eigen::MatrixXd(Z.rows(), k);
  std::uniform_int_distribution<Eigen::Index> first(0, n - 1);
  centres->col(0) = Z.col(first(rng));
  Eigen::VectorXd d2 = (Z.colwise() - centres->col(0)).colwise().squaredNorm().transpose();
  for (int c = 1; c < k; ++c) {
    const double total = d2.sum();
    Eigen::Index pick = 0;
    if (total > 0) {
      double u = std::uniform_real_distribution<double>(0, total)(rng);
      for (pick = 0; pick < n - 1; ++pick) {
        u -= d2[pick];
        if (u <= 0) break;
      }
    } else {
      pick = first(rng);
    }
    centres->col(c) = Z.col(pick);
    d2 = d2.cwiseMin((Z.colwise() - centres->col(c)).colwise().squaredNorm().transpose());
  }
  std::vector<int> label(static_cast<std::size_t>(n), 0);
  for (int it = 0; it <= iterations; ++it) {
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Index best = 0;
      (centres->colwise() - Z.col(i)).colwise().squaredNorm().minCoeff(&best);
      label[static_cast<std::size_t>(i)] = static_cast<int>(best);
    }
    if (it == iterations) break;
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(Z.rows(), k);
    Eigen::VectorXd count = Eigen::VectorXd::Zero(k);
    for (Eigen::Index i = 0; i < n; ++i) {
      sum.col(label[static_cast<std::size_t>(i)]) += Z.col(i);
      count[label[static_cast<std::size_t>(i)]] += 1;
    }
    for (int c = 0; c < k; ++c) {
      if (count[c] > 0) centres->col(c) = sum.col(c) / count[c];
    }
  }
  return label;
}

}  // namespace

GaussianMixture::GaussianMixture(std::vector<GaussianComponent> components) : components_(std::move(components)) {
  if (components_.empty()) fail("no components");
  const Eigen::Index d = components_.front().mean.size();
  if (d < 1) fail("components of dimension 0");
  double total = 0;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const GaussianComponent& c = components_[k];
    const std::string name = "component " + std::to_string(k);
    if (c.mean.size() != d || c.covariance.rows() != d || c.covariance.cols() != d) fail(name + ": wrong dimension");
    if (!std::isfinite(c.weight) || c.weight < 0) fail(name + ": weight must be finite and >= 0");
    if (!c.mean.allFinite() || !c.covariance.allFinite()) fail(name + ": not finite");
    if ((c.covariance - c.covariance.transpose()).cwiseAbs().maxCoeff() >
        1e-9 * std::max(1.0, c.covariance.cwiseAbs().maxCoeff())) {
      fail(name + ": covariance is not symmetric");
    }
    total += c.weight;
  }
  if (std::abs(total - 1) > 1e-6) fail("weights sum to " + std::to_string(total) + ", not 1");
  for (GaussianComponent& c : components_) c.weight /= total;
  prepare();
}

void GaussianMixture::prepare() {
  chol_.clear();
  log_norm_.clear();
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const Eigen::LLT<Eigen::MatrixXd> llt(components_[k].covariance);
    if (llt.info() != Eigen::Success || !(llt.matrixL().toDenseMatrix().diagonal().array() > 0).all()) {
      fail("component " + std::to_string(k) + ": covariance is not positive definite");
    }
    chol_.push_back(llt.matrixL());
    log_norm_.push_back(-0.5 * static_cast<double>(dimension()) * std::log(2 * std::numbers::pi) -
                        chol_.back().diagonal().array().log().sum());
  }
}

GaussianMixture GaussianMixture::fit(const Eigen::MatrixXd& data, const GmmFitOptions& options,
                                     GmmFitReport* report) {
  const Eigen::Index n = data.rows(), D = data.cols();
  const int K = options.components;
  if (K < 1) fail("components must be >= 1");
  if (D < 1) fail("data have no columns");
  if (!data.allFinite()) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!data.row(i).allFinite()) fail("data row " + std::to_string(i) + " is not finite");
    }
  }
  if (n < 2 || n < static_cast<Eigen::Index>(K) * (D + 1)) {
    fail(std::to_string(n) + " points for " + std::to_string(K) + " components in " + std::to_string(D) +
         " dimensions (at least components x (dimensions + 1) needed)");
  }
  if (!(options.variance_floor > 0)) fail("variance_floor must be > 0");
  // Standardise: Z = (X - offset) / scale, column-major D x n for the linear algebra.
  const Eigen::RowVectorXd offset = data.colwise().mean();
  Eigen::VectorXd scale(D);
  for (Eigen::Index d = 0; d < D; ++d) {
    scale[d] = std::sqrt((data.col(d).array() - offset[d]).square().mean());
    if (!(scale[d] > 0)) fail("dimension " + std::to_string(d) + " has no spread");
  }
  const Eigen::MatrixXd Z = ((data.rowwise() - offset).array().rowwise() / scale.transpose().array()).transpose();
  const double log_scale = scale.array().log().sum();  // mean LL in data units = in standardised units - this

  std::mt19937_64 rng(options.seed);
  Eigen::MatrixXd centres;
  const std::vector<int> label = kmeans(Z, K, options.kmeans_iterations, rng, &centres);
  std::vector<double> w(static_cast<std::size_t>(K));
  std::vector<Eigen::VectorXd> mu(static_cast<std::size_t>(K));
  std::vector<Eigen::MatrixXd> S(static_cast<std::size_t>(K)), L(static_cast<std::size_t>(K));
  for (int k = 0; k < K; ++k) {
    Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(D, D);
    double count = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (label[static_cast<std::size_t>(i)] != k) continue;
      const Eigen::VectorXd v = Z.col(i) - centres.col(k);
      scatter += v * v.transpose();
      count += 1;
    }
    const std::size_t kk = static_cast<std::size_t>(k);
    // Every component gets some weight at the start (an empty k-means cell starts small but alive).
    w[kk] = std::max(count, 1.0) / static_cast<double>(n);
    mu[kk] = centres.col(k);
    S[kk] = clamp_eigenvalues(count >= 2 ? Eigen::MatrixXd(scatter / count)
                                         : Eigen::MatrixXd(0.1 * Eigen::MatrixXd::Identity(D, D)),
                              options.variance_floor);
  }
  double wsum = 0;
  for (double v : w) wsum += v;
  for (double& v : w) v /= wsum;

  GmmFitReport local;
  GmmFitReport& rep = report != nullptr ? *report : local;
  rep = {};
  Eigen::MatrixXd logp(n, K);
  for (int it = 0;; ++it) {
    // E-step: responsibilities and the log-likelihood of the current parameters.
    for (int k = 0; k < K; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      if (w[kk] <= 0) {
        logp.col(k).setConstant(kNegInf);
        continue;
      }
      L[kk] = Eigen::LLT<Eigen::MatrixXd>(S[kk]).matrixL();
      logp.col(k) = log_gaussian_columns(Z, mu[kk], L[kk]).array() + std::log(w[kk]);
    }
    // Row-wise log-sum-exp over the components, vectorised; differences below -700 (and -inf: no weight) are
    // clamped there, which keeps exp() off subnormal numbers (slow) at a relative cost of 1e-304.
    const Eigen::VectorXd row_max = logp.rowwise().maxCoeff();
    Eigen::MatrixXd resp = (logp.colwise() - row_max).array().max(-700.0).exp().matrix();
    const Eigen::VectorXd row_sum = resp.rowwise().sum();
    resp.array().colwise() /= row_sum.array();
    const double ll = (row_max.array() + row_sum.array().log()).sum();
    rep.log_likelihood.push_back(ll / static_cast<double>(n) - log_scale);
    if (it > 0 && rep.log_likelihood.back() - rep.log_likelihood[rep.log_likelihood.size() - 2] < options.tolerance) {
      rep.converged = true;
      break;
    }
    if (it >= options.max_iterations) break;
    rep.iterations = it + 1;
    // M-step: weights, means, floored covariances.
    for (int k = 0; k < K; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const double nk = resp.col(k).sum();
      if (!(nk > 1e-12)) {
        w[kk] = 0;
        continue;
      }
      w[kk] = nk / static_cast<double>(n);
      mu[kk] = Z * resp.col(k) / nk;
      const Eigen::MatrixXd C = Z.colwise() - mu[kk];
      S[kk] = clamp_eigenvalues((C * resp.col(k).asDiagonal() * C.transpose()) / nk, options.variance_floor);
    }
  }
  // Back to data units; components without weight are dropped.
  std::vector<GaussianComponent> out;
  const Eigen::MatrixXd Ds = scale.asDiagonal();
  for (int k = 0; k < K; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    if (w[kk] <= 0) continue;
    GaussianComponent c;
    c.weight = w[kk];
    c.mean = offset.transpose() + scale.cwiseProduct(mu[kk]);
    c.covariance = Ds * S[kk] * Ds;
    c.covariance = 0.5 * (c.covariance + c.covariance.transpose());
    out.push_back(std::move(c));
  }
  double total = 0;
  for (const auto& c : out) total += c.weight;
  for (auto& c : out) c.weight /= total;
  return GaussianMixture(std::move(out));
}

double GaussianMixture::log_density(const Eigen::VectorXd& x) const {
  Eigen::VectorXd terms(static_cast<Eigen::Index>(components_.size()));
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const GaussianComponent& c = components_[k];
    if (c.weight <= 0) {
      terms[static_cast<Eigen::Index>(k)] = kNegInf;
      continue;
    }
    const Eigen::VectorXd y = chol_[k].triangularView<Eigen::Lower>().solve(x - c.mean);
    terms[static_cast<Eigen::Index>(k)] = std::log(c.weight) + log_norm_[k] - 0.5 * y.squaredNorm();
  }
  return log_sum_exp(terms);
}

double GaussianMixture::mean_log_likelihood(const Eigen::MatrixXd& data) const {
  double s = 0;
  for (Eigen::Index i = 0; i < data.rows(); ++i) s += log_density(data.row(i).transpose());
  return s / static_cast<double>(data.rows());
}

Eigen::VectorXd GaussianMixture::responsibilities(const Eigen::VectorXd& x) const {
  Eigen::VectorXd terms(static_cast<Eigen::Index>(components_.size()));
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const GaussianComponent& c = components_[k];
    const Eigen::VectorXd y = chol_[k].triangularView<Eigen::Lower>().solve(x - c.mean);
    terms[static_cast<Eigen::Index>(k)] =
        c.weight > 0 ? std::log(c.weight) + log_norm_[k] - 0.5 * y.squaredNorm() : kNegInf;
  }
  return (terms.array() - log_sum_exp(terms)).exp();
}

GaussianMixture GaussianMixture::conditional(const Eigen::VectorXd& a) const {
  const Eigen::Index m = a.size(), D = dimension(), r = D - m;
  if (m < 1 || m >= D) fail("conditioning on " + std::to_string(m) + " of " + std::to_string(D) + " coordinates");
  if (!a.allFinite()) fail("conditioning value is not finite");
  std::vector<GaussianComponent> out;
  Eigen::VectorXd logw(static_cast<Eigen::Index>(components_.size()));
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const GaussianComponent& c = components_[k];
    const Eigen::LLT<Eigen::MatrixXd> saa(c.covariance.topLeftCorner(m, m));
    const Eigen::MatrixXd Sba = c.covariance.bottomLeftCorner(r, m);
    const Eigen::VectorXd da = a - c.mean.head(m);
    GaussianComponent g;
    g.mean = c.mean.tail(r) + Sba * saa.solve(da);
    g.covariance = c.covariance.bottomRightCorner(r, r) - Sba * saa.solve(Sba.transpose());
    g.covariance = 0.5 * (g.covariance + g.covariance.transpose());
    const Eigen::VectorXd y = saa.matrixL().solve(da);
    const Eigen::MatrixXd La = saa.matrixL();
    logw[static_cast<Eigen::Index>(k)] =
        c.weight > 0 ? std::log(c.weight) - 0.5 * static_cast<double>(m) * std::log(2 * std::numbers::pi) -
                           La.diagonal().array().log().sum() - 0.5 * y.squaredNorm()
                     : kNegInf;
    out.push_back(std::move(g));
  }
  const double lse = log_sum_exp(logw);
  if (!std::isfinite(lse)) fail("conditioning value has zero density under every component");
  for (std::size_t k = 0; k < out.size(); ++k) out[k].weight = std::exp(logw[static_cast<Eigen::Index>(k)] - lse);
  double total = 0;
  for (const auto& c : out) total += c.weight;
  for (auto& c : out) c.weight /= total;
  return GaussianMixture(std::move(out));
}

Eigen::VectorXd GaussianMixture::mean() const {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(dimension());
  for (const auto& c : components_) m += c.weight * c.mean;
  return m;
}

Eigen::MatrixXd GaussianMixture::covariance() const {
  const Eigen::VectorXd m = mean();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(dimension(), dimension());
  for (const auto& c : components_) C += c.weight * (c.covariance + (c.mean - m) * (c.mean - m).transpose());
  return C;
}

int GaussianMixture::sample_component(std::mt19937_64& rng) const {
  double u = std::uniform_real_distribution<double>(0, 1)(rng);
  for (std::size_t k = 0; k < components_.size(); ++k) {
    u -= components_[k].weight;
    if (u < 0) return static_cast<int>(k);
  }
  for (std::size_t k = components_.size(); k-- > 0;) {
    if (components_[k].weight > 0) return static_cast<int>(k);
  }
  return 0;
}

Eigen::VectorXd GaussianMixture::sample(std::mt19937_64& rng) const {
  const std::size_t k = static_cast<std::size_t>(sample_component(rng));
  std::normal_distribution<double> normal(0, 1);
  Eigen::VectorXd z(dimension());
  for (Eigen::Index i = 0; i < z.size(); ++i) z[i] = normal(rng);
  return components_[k].mean + chol_[k] * z;
}

}  // namespace twinslam::sim::learn
