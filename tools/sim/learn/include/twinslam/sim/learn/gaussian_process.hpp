#pragma once
// Gaussian-process regression of a scalar against a scalar (issue 13, `gnss.model: learned`: the number of satellites
// received against the height above ground).
//
// Prior: y(x) = m + f(x) + e, f ~ GP(0, k), k(x, x') = s2 exp(-(x - x')^2 / (2 l^2)) (RBF), e ~ N(0, n2) white.
// m is the training mean. The hyper-parameters (s2, l, n2) maximise the log marginal likelihood
//   log p(y | x) = -1/2 r^T K_y^-1 r - 1/2 log|K_y| - N/2 log(2 pi),   K_y = K + n2 I,   r = y - m.
// For a given length scale l and noise-to-signal ratio q = n2 / s2 the best s2 has a closed form, so the search runs
// over (l, q) only: a log-spaced grid, then a pattern search around its best cell that halves its steps.
//
// Large training sets are reduced to at most max_points groups of consecutive inputs (sorted, equal counts), each
// represented by its mean input, its mean output and its count c: the output mean of c observations of the same f
// has noise n2 / c (per-point noise n2 / c_i on the diagonal), and the full likelihood is that of the group means
// times the within-group scatter S: log p(y) = log p(ybar) - S / (2 n2) - sum_g ((c_g - 1) log(2 pi n2) + log c_g) / 2.
// Inputs within a group are taken as equal (they span a small fraction of the length scale when groups are small).
// Unlike a random subsample this keeps every observation, so the mean is not off where data are sparse; a fit costs
// a few hundred Cholesky factorizations of a matrix of at most max_points square (well under a second).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace twinslam::sim::learn {

struct GpHyperParameters {
  double mean = 0;           // m: the constant prior mean [units of y]
  double signal_var = 1;     // s2 [units of y ^ 2]
  double length_scale = 1;   // l [units of x]
  double noise_var = 0.1;    // n2 [units of y ^ 2]
};

struct GpPrediction {
  double mean = 0;           // E[y(x)] = m + E[f(x)]
  double var_f = 0;          // variance of f(x) given the data (the model's uncertainty)
  double var_y = 0;          // var_f + n2: where a new observation falls
};

struct GpFitOptions {
  std::size_t max_points = 250;      // at most this many groups of consecutive inputs; 0 = every point its own
  int grid_length_scales = 10;       // log-spaced in [length_range_lo, length_range_hi] x (max x - min x)
  double length_range_lo = 0.01, length_range_hi = 2.0;
  int grid_ratios = 7;               // q = n2 / s2, log-spaced in [ratio_lo, ratio_hi]
  double ratio_lo = 1e-4, ratio_hi = 1e2;
  int refine_rounds = 4;             // pattern search: step halvings after the grid
};

class GaussianProcess {
 public:
  // The fitted model of (x, y); throws InputError "gaussian process: ..." with fewer than 3 points, sizes that differ,
  // a non-finite value or all x equal.
  static GaussianProcess fit(const std::vector<double>& x, const std::vector<double>& y,
                             const GpFitOptions& options = {});

  // A model with given hyper-parameters over given training points (e.g. read back from a file); the same checks.
  // counts: how many observations each point averages (its noise is n2 / count); empty = 1 each.
  GaussianProcess(std::vector<double> x, std::vector<double> y, const GpHyperParameters& hyper,
                  std::vector<double> counts = {});

  GpPrediction predict(double x) const;

  const GpHyperParameters& hyper() const { return hyper_; }
  const std::vector<double>& x() const { return x_; }   // training points used (group means after grouping)
  const std::vector<double>& y() const { return y_; }
  const std::vector<double>& counts() const { return counts_; }
  // Of the points the model holds (the group means, without the within-group scatter).
  double log_marginal_likelihood() const { return lml_; }

  // log p(y | x) for these hyper-parameters (mean taken from hyper.mean); -inf if K_y is not positive definite.
  static double log_marginal_likelihood(const std::vector<double>& x, const std::vector<double>& y,
                                        const GpHyperParameters& hyper);

 private:
  void factorize();

  std::vector<double> x_, y_, counts_;
  GpHyperParameters hyper_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::VectorXd alpha_;      // K_y^-1 (y - m)
  double lml_ = 0;
};

}  // namespace twinslam::sim::learn
