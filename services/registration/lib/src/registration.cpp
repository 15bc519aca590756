// register_cloud: the stages and the acceptance tests (see registration.hpp).
#include "twinslam/registration/registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <Eigen/Cholesky>

#include "twinslam/core/error.hpp"
#include "twinslam/geometry/information_order.hpp"
#include "twinslam/geometry/so3.hpp"
#include "twinslam/registration/yaw_search.hpp"

namespace twinslam::registration {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::string fmt(const char* format, double a, double b) {
  char buf[200];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

void check_covariance(const Matrix6d& S) {
  if (!S.allFinite() || (S - S.transpose()).norm() > 1e-9 * std::max(1.0, S.norm())) {
    throw InputError("registration: prior covariance must be finite and symmetric");
  }
  if (Eigen::LLT<Matrix6d>(S).info() != Eigen::Success) {
    throw InputError("registration: prior covariance must be positive definite");
  }
}

// The acceptance tests after ICP, most telling first (no twin near the cloud is 'too few inliers', not 'not
// converged', even though ICP stopped early). Returns false with status/reason set.
bool reject_fit(const RegistrationConfig& c, const IcpResult& icp, RegistrationResult& r) {
  const auto fail = [&](RegistrationStatus s, std::string why) {
    r.status = s;
    r.reason = std::move(why);
    return false;
  };
  if (r.inliers < static_cast<std::size_t>(c.min_inliers)) {
    return fail(RegistrationStatus::kTooFewInliers,
                fmt("%.0f inliers < min_inliers %.0f", static_cast<double>(r.inliers), c.min_inliers));
  }
  if (!icp.converged) {
    return fail(RegistrationStatus::kNotConverged,
                fmt("ICP did not converge in %.0f iterations (limit %.0f)", icp.iterations, c.max_iterations));
  }
  if (r.fitness < c.min_fitness) {
    return fail(RegistrationStatus::kFitnessTooLow, fmt("fitness %.3f < min_fitness %.3f", r.fitness, c.min_fitness));
  }
  if (r.rmse_m > c.max_rmse_m) {
    return fail(RegistrationStatus::kRmseTooLarge,
                fmt("inlier RMSE %.3f m > max_rmse_m %.3f m", r.rmse_m, c.max_rmse_m));
  }
  return true;
}

bool reject_heading(const YawSearchResult& search, RegistrationResult& r) {
  if (!search.ambiguous) return true;
  r.status = RegistrationStatus::kDegenerate;
  r.heading_ambiguous = true;
  char buf[200];
  std::snprintf(buf, sizeof buf, "heading ambiguous: %zu points fit another heading, %zu the best (%d ICP starts)",
                search.runner_up, search.support, search.starts);
  r.reason = buf;
  return false;
}

bool reject_geometry(const RegistrationConfig& c, const std::optional<Matrix6d>& prior, RegistrationResult& r) {
  if (r.details.zero_directions > c.max_zero_directions) {
    r.status = RegistrationStatus::kDegenerate;
    r.reason = fmt("%.0f poorly observed directions > max_zero_directions %.0f", r.details.zero_directions,
                   c.max_zero_directions);
    return false;
  }
  if (c.max_position_sigma_m > 0.0) {
    const double sigma_m = geometry::observed_position_sigma_m(r.details.information);
    if (sigma_m > c.max_position_sigma_m) {
      r.status = RegistrationStatus::kDegenerate;
      r.reason = fmt("predicted position sigma %.3f m > max_position_sigma_m %.3f m", sigma_m, c.max_position_sigma_m);
      return false;
    }
  }
  if (prior) {
    Matrix6d S = *prior;
    S.diagonal().head<3>().array() += std::pow(c.mahalanobis_floor_deg * M_PI / 180.0, 2);
    S.diagonal().tail<3>().array() += c.mahalanobis_floor_m * c.mahalanobis_floor_m;
    r.mahalanobis_sq = r.correction_xi.dot(Eigen::LLT<Matrix6d>(S).solve(r.correction_xi));
    if (r.mahalanobis_sq > c.max_mahalanobis_sq) {
      r.status = RegistrationStatus::kCorrectionTooLarge;
      r.reason = fmt("correction's Mahalanobis distance^2 %.2f > max_mahalanobis_sq %.2f", r.mahalanobis_sq,
                     c.max_mahalanobis_sq);
      return false;
    }
  }
  return true;
}

// The first correspondence gate that covers the estimator's own position uncertainty: initial_threshold_sigmas of
// its largest position sigma, within [initial_threshold_m, max_initial_threshold_m].
double covering_first_gate_m(const RegistrationConfig& config, const std::optional<Matrix6d>& prior_covariance) {
  if (!prior_covariance || !(config.initial_threshold_sigmas > 0.0)) return config.initial_threshold_m;
  const double sigma_m = std::sqrt(std::max(prior_covariance->bottomRightCorner<3, 3>().diagonal().maxCoeff(), 0.0));
  return std::clamp(config.initial_threshold_sigmas * sigma_m, config.initial_threshold_m,
                    config.max_initial_threshold_m);
}

}  // namespace

const char* status_name(RegistrationStatus status) {
  switch (status) {
    case RegistrationStatus::kAccepted: return "accepted";
    case RegistrationStatus::kTooFewPoints: return "too_few_points";
    case RegistrationStatus::kNotConverged: return "not_converged";
    case RegistrationStatus::kTooFewInliers: return "too_few_inliers";
    case RegistrationStatus::kFitnessTooLow: return "fitness_too_low";
    case RegistrationStatus::kRmseTooLarge: return "rmse_too_large";
    case RegistrationStatus::kDegenerate: return "degenerate";
    case RegistrationStatus::kCorrectionTooLarge: return "correction_too_large";
  }
  return "?";
}

RegistrationResult register_cloud(const RegistrationConfig& config, const TwinTileIndex& index,
                                  const SourceInput& source, const std::optional<Matrix6d>& prior_covariance,
                                  const std::optional<ScalePrior>& scale_prior) {
  if (prior_covariance) check_covariance(*prior_covariance);
  RegistrationResult r;
  const auto t0 = Clock::now();
  const SourceCloud cloud = preprocess(config, source);
  r.time.preprocess_ms = ms_since(t0);
  r.pivot_W = cloud.p_WB;
  r.source_points = cloud.p_W.size();
  if (r.source_points < static_cast<std::size_t>(config.min_points)) {
    r.status = RegistrationStatus::kTooFewPoints;
    r.reason = fmt("%.0f source points after preprocessing < min_points %.0f", static_cast<double>(r.source_points),
                   config.min_points);
    r.time.total_ms = ms_since(t0);
    return r;
  }
  const auto t1 = Clock::now();
  std::optional<double> heading_sigma_deg;
  if (prior_covariance) heading_sigma_deg = std::sqrt((*prior_covariance)(2, 2)) * 180.0 / M_PI;  // about W's z
  YawSearchResult search =
      run_icp_with_yaw_search(config, index, cloud.p_W, cloud.cov_W, cloud.p_WB, heading_sigma_deg, scale_prior);
  int starts = search.starts;
  // While the estimator is unsure of its position ICP also runs from the wider first gate; the result more of the
  // twin supports wins, the fixed gate's on a tie. The wide gate alone found the height where the fixed one could
  // not (city-loops, tracked images), but in Delft's narrow streets its extra correspondences biased some
  // registrations 0.5-0.9 m (8 of 258 accepted > 0.5 m off, none with the fixed gate).
  if (const double gate_m = covering_first_gate_m(config, prior_covariance); gate_m > config.initial_threshold_m) {
    RegistrationConfig wide = config;
    wide.initial_threshold_m = gate_m;
    YawSearchResult widened =
        run_icp_with_yaw_search(wide, index, cloud.p_W, cloud.cov_W, cloud.p_WB, heading_sigma_deg, scale_prior);
    starts += widened.starts;
    if (widened.support > search.support) search = std::move(widened);
  }
  const IcpResult& icp = search.icp;
  r.time.icp_ms = ms_since(t1);
  r.yaw_starts = starts;
  r.correction_W = icp.correction_W;
  r.correction_xi << geometry::so3_log(icp.dR), icp.dp;
  r.rmse_m = icp.rmse_m;
  r.inliers = icp.inliers.size();
  r.fitness = static_cast<double>(r.inliers) / static_cast<double>(r.source_points);
  r.iterations = icp.iterations;
  r.scale = icp.scale;
  const auto t2 = Clock::now();
  r.details = compute_information(config, icp.inliers, icp.rmse_m, icp.sigma_m);
  r.information_eigenvalues = r.details.eigenvalues;
  r.time.hessian_ms = ms_since(t2);
  if (reject_fit(config, icp, r) && reject_heading(search, r) && reject_geometry(config, prior_covariance, r)) {
    r.status = RegistrationStatus::kAccepted;
    r.information = r.details.information;
  }
  r.time.total_ms = ms_since(t0);
  return r;
}

}  // namespace twinslam::registration
