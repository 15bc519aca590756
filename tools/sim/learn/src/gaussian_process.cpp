#include "twinslam/sim/learn/gaussian_process.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <string>

#include "twinslam/core/error.hpp"

namespace twinslam::sim::learn {
namespace {

void check_training_set(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) {
    throw InputError("gaussian process: " + std::to_string(x.size()) + " inputs but " + std::to_string(y.size()) +
                     " outputs");
  }
  if (x.size() < 3) {
    throw InputError("gaussian process: " + std::to_string(x.size()) + " training points (at least 3 needed)");
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw InputError("gaussian process: training point " + std::to_string(i) + " is not finite");
    }
  }
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  if (!(*hi > *lo)) throw InputError("gaussian process: all inputs are equal (no length scale to fit)");
}

// Squared distances between the inputs.
Eigen::MatrixXd squared_distances(const std::vector<double>& x) {
  const Eigen::Map<const Eigen::ArrayXd> v(x.data(), static_cast<Eigen::Index>(x.size()));
  const Eigen::Index n = v.size();
  return (v.replicate(1, n) - v.transpose().replicate(n, 1)).square().matrix();
}

// Unit-variance kernel matrix plus q / c_i on the diagonal, from the squared distances.
Eigen::MatrixXd unit_kernel(const Eigen::MatrixXd& d2, const Eigen::VectorXd& inv_counts, double length_scale,
                            double q) {
  // Terms below exp(-40) are zero against the diagonal; clamping them keeps exp() away from subnormal numbers (slow).
  Eigen::MatrixXd K = (d2.array() * (-0.5 / (length_scale * length_scale))).max(-40.0).exp().matrix();
  K.diagonal() += q * inv_counts;
  return K;
}

struct Profiled {
  double lml = -std::numeric_limits<double>::infinity();
  double signal_var = 0;
};

// What the likelihood needs of the (grouped) training set.
struct Grouped {
  Eigen::MatrixXd d2;            // squared distances between the group inputs
  Eigen::VectorXd r;             // group mean outputs minus the prior mean
  Eigen::VectorXd inv_counts;    // 1 / c_g
  double within_ss = 0;          // S: scatter of the outputs about their group means
  double total = 0;              // N: observations
  double log_counts = 0;         // sum_g log c_g
};

// The full-data log marginal likelihood maximised over s2 for given (l, q): with n2 = q s2,
//   L = -Q / (2 s2) - S / (2 q s2) - (N / 2) log s2 - logdet(K_1 + q C^-1) / 2 - (N - G) / 2 log q
//       - N / 2 log(2 pi) - sum log c_g / 2,      Q = r^T (K_1 + q C^-1)^-1 r,
// maximal at s2 = (Q + S / q) / N.
Profiled profiled_lml(const Grouped& g, double length_scale, double q, double signal_var_floor) {
  Eigen::LLT<Eigen::MatrixXd> llt(unit_kernel(g.d2, g.inv_counts, length_scale, q));
  if (llt.info() != Eigen::Success) return {};
  const double G = static_cast<double>(g.r.size()), N = g.total;
  const double quad = g.r.dot(llt.solve(g.r));
  const double s2 = std::max((quad + g.within_ss / q) / N, signal_var_floor);
  const double log_det_unit = 2 * llt.matrixLLT().diagonal().array().log().sum();
  Profiled p;
  p.signal_var = s2;
  p.lml = -0.5 * (quad + g.within_ss / q) / s2 - 0.5 * N * std::log(s2) - 0.5 * log_det_unit -
          0.5 * (N - G) * std::log(q) - 0.5 * N * std::log(2 * std::numbers::pi) - 0.5 * g.log_counts;
  return p;
}

}  // namespace

GaussianProcess::GaussianProcess(std::vector<double> x, std::vector<double> y, const GpHyperParameters& hyper,
                                 std::vector<double> counts)
    : x_(std::move(x)), y_(std::move(y)), counts_(std::move(counts)), hyper_(hyper) {
  check_training_set(x_, y_);
  if (counts_.empty()) counts_.assign(x_.size(), 1.0);
  if (counts_.size() != x_.size()) throw InputError("gaussian process: counts and inputs differ in number");
  for (const double c : counts_) {
    if (!(c >= 1) || !std::isfinite(c)) throw InputError("gaussian process: counts must be finite and >= 1");
  }
  if (!(hyper_.signal_var > 0) || !(hyper_.length_scale > 0) || !(hyper_.noise_var > 0) ||
      !std::isfinite(hyper_.mean) || !std::isfinite(hyper_.signal_var) || !std::isfinite(hyper_.length_scale) ||
      !std::isfinite(hyper_.noise_var)) {
    throw InputError("gaussian process: hyper-parameters must be finite, variances and length scale > 0");
  }
  factorize();
}

void GaussianProcess::factorize() {
  const double q = hyper_.noise_var / hyper_.signal_var;
  const Eigen::VectorXd inv_counts =
      Eigen::Map<const Eigen::VectorXd>(counts_.data(), static_cast<Eigen::Index>(counts_.size())).cwiseInverse();
  llt_.compute(hyper_.signal_var * unit_kernel(squared_distances(x_), inv_counts, hyper_.length_scale, q));
  if (llt_.info() != Eigen::Success) throw InputError("gaussian process: kernel matrix is not positive definite");
  Eigen::VectorXd r(static_cast<Eigen::Index>(y_.size()));
  for (std::size_t i = 0; i < y_.size(); ++i) r[static_cast<Eigen::Index>(i)] = y_[i] - hyper_.mean;
  alpha_ = llt_.solve(r);
  const double n = static_cast<double>(r.size());
  lml_ = -0.5 * r.dot(alpha_) - llt_.matrixLLT().diagonal().array().log().sum() -
         0.5 * n * std::log(2 * std::numbers::pi);
}

double GaussianProcess::log_marginal_likelihood(const std::vector<double>& x, const std::vector<double>& y,
                                                const GpHyperParameters& hyper) {
  try {
    return GaussianProcess(x, y, hyper).lml_;
  } catch (const InputError&) {
    return -std::numeric_limits<double>::infinity();
  }
}

GaussianProcess GaussianProcess::fit(const std::vector<double>& x_all, const std::vector<double>& y_all,
                                     const GpFitOptions& options) {
  check_training_set(x_all, y_all);
  // Groups of consecutive inputs (sorted; stable, so the result does not depend on the input order of ties).
  std::vector<std::size_t> order(x_all.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x_all[a] < x_all[b]; });
  const std::size_t n_all = x_all.size();
  const std::size_t per_group =
      options.max_points > 0 && n_all > options.max_points ? (n_all + options.max_points - 1) / options.max_points : 1;
  std::vector<double> x, y, counts;
  const double mean = std::accumulate(y_all.begin(), y_all.end(), 0.0) / static_cast<double>(n_all);
  Grouped g;
  g.total = static_cast<double>(n_all);
  double var_y = 0;
  for (std::size_t start = 0; start < n_all; start += per_group) {
    const std::size_t end = std::min(n_all, start + per_group);
    double sx = 0, sy = 0;
    for (std::size_t k = start; k < end; ++k) {
      sx += x_all[order[k]];
      sy += y_all[order[k]];
      var_y += (y_all[order[k]] - mean) * (y_all[order[k]] - mean) / g.total;
    }
    const double c = static_cast<double>(end - start);
    x.push_back(sx / c);
    y.push_back(sy / c);
    counts.push_back(c);
    for (std::size_t k = start; k < end; ++k) g.within_ss += (y_all[order[k]] - y.back()) * (y_all[order[k]] - y.back());
    g.log_counts += std::log(c);
  }
  check_training_set(x, y);  // the group means may have all x equal
  g.r.resize(static_cast<Eigen::Index>(y.size()));
  for (std::size_t i = 0; i < y.size(); ++i) g.r[static_cast<Eigen::Index>(i)] = y[i] - mean;
  g.inv_counts = Eigen::Map<const Eigen::VectorXd>(counts.data(), static_cast<Eigen::Index>(counts.size())).cwiseInverse();
  g.d2 = squared_distances(x);
  // Constant outputs: no signal to fit; keep the variances finite and small against the output's scale.
  const double scale2 = var_y > 0 ? var_y : std::max(1.0, mean * mean) * 1e-6;
  const double floor = 1e-9 * scale2;
  const auto [xlo, xhi] = std::minmax_element(x.begin(), x.end());
  const double span = *xhi - *xlo;

  // Grid over log l and log q, then a pattern search around the best point.
  double best_ll = std::log(options.length_range_lo * span), best_lq = std::log(options.ratio_lo);
  Profiled best;
  const auto evaluate = [&](double ll, double lq) { return profiled_lml(g, std::exp(ll), std::exp(lq), floor); };
  const int gl = std::max(2, options.grid_length_scales), gq = std::max(2, options.grid_ratios);
  const double dl = (std::log(options.length_range_hi) - std::log(options.length_range_lo)) / (gl - 1);
  const double dq = (std::log(options.ratio_hi) - std::log(options.ratio_lo)) / (gq - 1);
  for (int i = 0; i < gl; ++i) {
    for (int j = 0; j < gq; ++j) {
      const double ll = std::log(options.length_range_lo * span) + i * dl, lq = std::log(options.ratio_lo) + j * dq;
      const Profiled p = evaluate(ll, lq);
      if (p.lml > best.lml) {
        best = p;
        best_ll = ll;
        best_lq = lq;
      }
    }
  }
  if (!std::isfinite(best.lml)) throw InputError("gaussian process: no hyper-parameters give a valid kernel");
  double step_l = dl / 2, step_q = dq / 2;
  for (int round = 0; round < options.refine_rounds; ++round) {
    bool moved = true;
    for (int guard = 0; moved && guard < 8; ++guard) {
      moved = false;
      for (const auto& [sl, sq] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const double ll = best_ll + sl * step_l, lq = best_lq + sq * step_q;
        const Profiled p = evaluate(ll, lq);
        if (p.lml > best.lml + 1e-12 * std::abs(best.lml)) {
          best = p;
          best_ll = ll;
          best_lq = lq;
          moved = true;
        }
      }
    }
    step_l /= 2;
    step_q /= 2;
  }
  GpHyperParameters h;
  h.mean = mean;
  h.signal_var = best.signal_var;
  h.length_scale = std::exp(best_ll);
  h.noise_var = std::exp(best_lq) * best.signal_var;
  return GaussianProcess(std::move(x), std::move(y), h, std::move(counts));
}

GpPrediction GaussianProcess::predict(double x) const {
  const Eigen::Index n = static_cast<Eigen::Index>(x_.size());
  Eigen::VectorXd k(n);
  const double c = -0.5 / (hyper_.length_scale * hyper_.length_scale);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = x - x_[static_cast<std::size_t>(i)];
    k[i] = hyper_.signal_var * std::exp(c * d * d);
  }
  GpPrediction p;
  p.mean = hyper_.mean + k.dot(alpha_);
  const Eigen::VectorXd v = llt_.matrixL().solve(k);
  p.var_f = std::max(0.0, hyper_.signal_var - v.squaredNorm());
  p.var_y = p.var_f + hyper_.noise_var;
  return p;
}

}  // namespace twinslam::sim::learn
