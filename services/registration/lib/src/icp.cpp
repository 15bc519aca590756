// Point-to-plane ICP (see icp.hpp for the pivot, the residual and its Jacobian).
#include "twinslam/registration/icp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "twinslam/geometry/so3.hpp"

namespace twinslam::registration {
namespace {

constexpr double kMadToSigma = 1.4826;  // sigma of a Gaussian from its median absolute deviation

struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double s = 1.0;  // scale about the pivot (estimate_scale)
};

using Vector7d = Eigen::Matrix<double, 7, 1>;
using Matrix7d = Eigen::Matrix<double, 7, 7>;

// The nearest twin point of every source point within the gate, in source order. The searches are independent
// (in parallel on `threads`); the list is then compacted in order, so it does not depend on the thread count.
std::vector<Correspondence> associate(const RegistrationConfig& config, const TwinTileIndex& index,
                                      const std::vector<Eigen::Vector3d>& p_W, const std::vector<Eigen::Matrix3d>& cov_W,
                                      const Eigen::Vector3d& c, const Pose& pose, double gate) {
  std::vector<Correspondence> slot(p_W.size());
  std::vector<char> found(p_W.size(), 0);
  const auto n = static_cast<std::ptrdiff_t>(p_W.size());
#pragma omp parallel for num_threads(config.threads) schedule(static) if (config.threads > 1)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d a = pose.s * (pose.R * (p_W[k] - c)) + pose.t;
    const auto m = index.nearest(c + a, gate);
    if (!m) continue;
    const Eigen::Vector3d b = m->p_W - c;
    // The landmark's covariance turns with the correction: n^T R C R^T n.
    const double w = cov_W.empty() ? 1.0 : residual_weight(config, cov_W[k], pose.R.transpose() * m->n_W);
    slot[k] = {a, b, m->n_W, m->n_W.dot(a - b), m->distance_m, w};
    found[k] = 1;
  }
  std::vector<Correspondence> out;
  out.reserve(p_W.size());
  for (std::size_t k = 0; k < slot.size(); ++k)
    if (found[k]) out.push_back(slot[k]);
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Robust sigma of the correspondence distances (drives the gate) or of the weighted plane residuals sqrt(w) r
// (inliers, the adaptive information).
double robust_sigma(const std::vector<Correspondence>& corr, bool plane) {
  std::vector<double> v;
  v.reserve(corr.size());
  for (const Correspondence& k : corr) v.push_back(plane ? std::sqrt(k.weight) * std::abs(k.residual) : k.distance);
  return kMadToSigma * median(std::move(v));
}

// One Gauss-Newton step x = (w, v, sigma) (rotation, translation, log-scale) of the Geman-McClure-weighted eq. (2),
// for the update a' = e^sigma Exp(w) a + v; sigma stays 0 unless `with_scale`. The normal equations are solved in units
// where rotation and scale are scaled by the cloud's radius, so that a pseudo-inverse can leave out unobservable
// directions (a single plane; the scale column when not estimated) instead of taking a huge step along them. A single
// plane seen from afar leaves scale and the shift along its normal nearly inseparable (a scale about the keyframe
// moves it like a shift): ICP then does not settle within its iterations and the result is refused (not converged).
// The scale prior (ScalePrior) adds (ln s - mu)^2 k^2 / sigma^2 to the cost: the point residuals are in metres with
// weight 1 at r = 0, i.e. measured in units of the kernel k.
Vector7d gauss_newton_step(const std::vector<Correspondence>& corr, double kernel, bool with_scale, double log_scale,
                           const std::optional<ScalePrior>& prior) {
  Matrix7d JtJ = Matrix7d::Zero();
  Vector7d Jtr = Vector7d::Zero();
  double radius_sq = 0.0;
  const double k2 = kernel * kernel;
  for (const Correspondence& k : corr) {
    Vector7d J;
    J << k.a.cross(k.n), k.n, with_scale ? k.n.dot(k.a) : 0.0;
    const double d = k2 + k.residual * k.residual;
    const double w = k.weight * k2 * k2 / (d * d);  // Geman-McClure: rho'(r) / r, 1 at r = 0; times w_j
    JtJ.noalias() += w * J * J.transpose();
    Jtr.noalias() += w * J * k.residual;
    radius_sq += k.a.squaredNorm();
  }
  if (with_scale && prior) {
    const double w = k2 / (prior->sigma * prior->sigma);
    JtJ(6, 6) += w;
    Jtr(6) += w * (log_scale - prior->log_scale);
  }
  const double L = std::max(1.0, std::sqrt(radius_sq / static_cast<double>(corr.size())));
  Vector7d s;
  s << Eigen::Vector3d::Constant(1.0 / L), Eigen::Vector3d::Ones(), 1.0 / L;
  const Matrix7d Hs = s.asDiagonal() * JtJ * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix7d> eig(Hs);
  const double floor = 1e-9 * std::max(eig.eigenvalues().maxCoeff(), 1e-300);
  Vector7d inv = eig.eigenvalues();
  for (int i = 0; i < 7; ++i) inv(i) = inv(i) > floor ? 1.0 / inv(i) : 0.0;
  const Vector7d xs = -eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose() * (s.asDiagonal() * Jtr);
  return s.asDiagonal() * xs;
}

// The correspondences of the last iteration carried through its update x: a' = e^sigma Exp(w) a + v,
// the same twin points. Used once ICP has converged: the update is below 0.1 mm, so a fresh nearest-neighbour search
// would find the same points, and skipping it saves one association of the ~6 per registration.
std::vector<Correspondence> carry(std::vector<Correspondence> corr, const Vector7d& x, double gate) {
  const Eigen::Matrix3d dR = geometry::so3_exp(x.head<3>());
  const double ds = std::exp(x(6));
  std::vector<Correspondence> out;
  out.reserve(corr.size());
  for (Correspondence& k : corr) {
    k.a = ds * (dR * k.a) + x.segment<3>(3);
    k.distance = (k.a - k.b).norm();
    k.residual = k.n.dot(k.a - k.b);
    if (k.distance <= gate) out.push_back(k);
  }
  return out;
}

void finish(const RegistrationConfig& config, const std::vector<Correspondence>& corr, const Pose& pose, double gate,
            IcpResult& out) {
  out.correspondences = corr.size();
  out.threshold_m = gate;
  out.sigma_m = std::max(robust_sigma(corr, true), 1e-9);
  double sum_sq = 0.0;
  for (const Correspondence& k : corr) {
    if (std::sqrt(k.weight) * std::abs(k.residual) > config.threshold_sigmas * out.sigma_m) continue;
    out.inliers.push_back(k);
    sum_sq += k.residual * k.residual;
  }
  out.rmse_m = out.inliers.empty() ? 0.0 : std::sqrt(sum_sq / static_cast<double>(out.inliers.size()));
  out.dR = pose.R;
  out.dp = pose.t;
  out.scale = pose.s;
  out.correction_W = correction_about(pose.R, pose.t, out.pivot_W);
}

}  // namespace

double residual_weight(const RegistrationConfig& config, const Eigen::Matrix3d& cov_W, const Eigen::Vector3d& n_W) {
  const double surface_sq = config.surface_sigma_m * config.surface_sigma_m;
  if (!(surface_sq > 0.0)) return 1.0;  // surface_sigma_m 0: the landmarks' covariances are ignored
  return surface_sq / (surface_sq + std::max(0.0, n_W.dot(cov_W * n_W)));
}

Eigen::Isometry3d correction_about(const Eigen::Matrix3d& dR, const Eigen::Vector3d& dp,
                                   const Eigen::Vector3d& pivot_W) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = dR;
  T.translation() = pivot_W + dp - dR * pivot_W;
  return T;
}

IcpResult run_icp(const RegistrationConfig& config, const TwinTileIndex& index, const std::vector<Eigen::Vector3d>& p_W,
                  const std::vector<Eigen::Matrix3d>& cov_W, const Eigen::Vector3d& pivot_W,
                  const Eigen::Matrix3d& dR0, const std::optional<ScalePrior>& scale_prior) {
  IcpResult out;
  out.pivot_W = pivot_W;
  Pose pose;
  pose.R = dR0;
  double gate = config.initial_threshold_m;
  const double conv_rot = config.convergence_rotation_deg * M_PI / 180.0;
  // The log-scale converges with the rotation's threshold (1e-3 deg = 1.7e-5: 1.7 mm at 100 m).
  const auto small = [&](const Vector7d& v, double scale) {
    return v.head<3>().norm() < scale * conv_rot && v.segment<3>(3).norm() < scale * config.convergence_translation_m &&
           std::abs(v(6)) < scale * conv_rot;
  };
  std::vector<Correspondence> corr;
  Vector7d x = Vector7d::Zero(), x_prev = Vector7d::Constant(std::numeric_limits<double>::infinity());
  for (int it = 1; it <= config.max_iterations; ++it) {
    corr = associate(config, index, p_W, cov_W, pivot_W, pose, gate);
    if (corr.size() < 6) break;  // nothing to solve for: not converged
    // KISS-ICP's adaptive threshold: the gate follows 3 sigma of the distances (never growing, never below the
    // floor), and the kernel scale is that sigma, so far correspondences lose weight smoothly as alignment improves.
    const double sigma = std::max(robust_sigma(corr, false), config.min_threshold_m / config.threshold_sigmas);
    x = gauss_newton_step(corr, sigma, config.estimate_scale, std::log(pose.s), scale_prior);
    // Two correspondence sets that each pull the pose to the other's side make ICP alternate between two poses for
    // ever (bench_registration: steps of +-1 mm until the iteration limit, 1 % of its keyframes, the p99 time). When
    // this step undoes the last one and both are small (< 100 x the convergence thresholds: 1 cm, 0.1 deg), the
    // optimum is between them: take half the step and stop.
    const bool cycle = small(x + x_prev, 1.0) && small(x, 100.0);
    if (cycle) x *= 0.5;
    const Eigen::Matrix3d dR = geometry::so3_exp(x.head<3>());
    const double ds = std::exp(x(6));
    pose.R = geometry::so3_normalize(dR * pose.R);
    pose.t = ds * (dR * pose.t) + x.segment<3>(3);
    pose.s *= ds;
    gate = std::clamp(config.threshold_sigmas * sigma, config.min_threshold_m, gate);
    out.iterations = it;
    if (cycle || small(x, 1.0)) {
      out.converged = true;
      break;
    }
    x_prev = x;
  }
  std::vector<Correspondence> last = out.converged ? carry(std::move(corr), x, gate)
                                                  : associate(config, index, p_W, cov_W, pivot_W, pose, gate);
  finish(config, last, pose, gate, out);
  return out;
}

}  // namespace twinslam::registration
