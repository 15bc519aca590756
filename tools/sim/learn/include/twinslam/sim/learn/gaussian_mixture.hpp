#pragma once
// Gaussian mixture model with full covariances, fitted by expectation-maximisation (issue 13, `gnss.model: learned`:
// the joint density of height and a satellite's range error, from which the error is drawn given the height).
//
// Fit: the data are standardised per dimension (zero mean, unit standard deviation); k-means++ seeding (seeded) and a
// few Lloyd iterations give the initial means, weights and covariances; then EM. The M-step keeps every covariance's
// eigenvalues (in standardised units) at or above `variance_floor`: for a Gaussian the constrained maximiser of the
// expected complete-data log-likelihood has the eigenvectors of the weighted scatter matrix and its eigenvalues
// clamped to the floor, so each M-step is an exact maximisation over the constrained set and the log-likelihood never
// decreases (EM's guarantee holds; the report records it per iteration). A component that loses all its points keeps
// its parameters with weight 0 and is dropped at the end.
//
// Conditioning: for x = (a, b) with a the first m coordinates, p(b | a) is again a mixture, with weights
// w_k N(a; mu_ka, S_kaa) / sum_j (...), means mu_kb + S_kba S_kaa^-1 (a - mu_ka) and covariances
// S_kbb - S_kba S_kaa^-1 S_kab.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

namespace twinslam::sim::learn {

struct GmmFitOptions {
  int components = 8;
  int max_iterations = 300;
  double tolerance = 1e-7;         // stop when the mean log-likelihood per point gains less than this [nats]
  double variance_floor = 1e-4;    // lower bound of every covariance eigenvalue, in standardised units [-]
  int kmeans_iterations = 10;      // Lloyd iterations after the k-means++ seeding
  std::uint64_t seed = 1;
};

struct GmmFitReport {
  std::vector<double> log_likelihood;  // mean log-likelihood per point, after each EM iteration (first: the start)
  int iterations = 0;
  bool converged = false;
};

struct GaussianComponent {
  double weight = 0;
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
};

class GaussianMixture {
 public:
  GaussianMixture() = default;
  // Throws InputError "gaussian mixture: ..." when the components are empty, of different dimensions, a weight is
  // negative or the weights do not sum to 1 (within 1e-6; they are renormalised), a value is not finite, or a
  // covariance is not symmetric positive definite.
  explicit GaussianMixture(std::vector<GaussianComponent> components);

  // EM on the rows of `data` (n x D). Throws InputError "gaussian mixture: ..." on a non-finite value, fewer points
  // than components x (D + 1), fewer than 2 points, or a dimension with no spread.
  static GaussianMixture fit(const Eigen::MatrixXd& data, const GmmFitOptions& options = {},
                             GmmFitReport* report = nullptr);

  int dimension() const { return components_.empty() ? 0 : static_cast<int>(components_.front().mean.size()); }
  const std::vector<GaussianComponent>& components() const { return components_; }
  const Eigen::MatrixXd& cholesky(std::size_t k) const { return chol_[k]; }  // lower factor of covariance k

  double log_density(const Eigen::VectorXd& x) const;
  // Mean log-likelihood per row of data (n x D).
  double mean_log_likelihood(const Eigen::MatrixXd& data) const;
  // Responsibilities p(k | x), one per component.
  Eigen::VectorXd responsibilities(const Eigen::VectorXd& x) const;

  // The mixture of the remaining D - m coordinates given the first m = a.size() (1 <= m < D).
  GaussianMixture conditional(const Eigen::VectorXd& a) const;

  // Mean and covariance of the whole mixture.
  Eigen::VectorXd mean() const;
  Eigen::MatrixXd covariance() const;

  int sample_component(std::mt19937_64& rng) const;
  Eigen::VectorXd sample(std::mt19937_64& rng) const;

 private:
  std::vector<GaussianComponent> components_;
  std::vector<Eigen::MatrixXd> chol_;          // lower Cholesky factor of each covariance
  std::vector<double> log_norm_;               // log of each Gaussian's normalising constant
  void prepare();
};

}  // namespace twinslam::sim::learn
