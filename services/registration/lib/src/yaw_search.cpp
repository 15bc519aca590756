// Heading search around the estimator's heading (see yaw_search.hpp).
#include "twinslam/registration/yaw_search.hpp"

#include <algorithm>
#include <cmath>

namespace twinslam::registration {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

double heading_deg(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)) / kDegToRad; }

double wrapped_difference_deg(double a, double b) { return std::abs(std::fmod(a - b + 540.0, 360.0) - 180.0); }

}  // namespace

std::vector<double> yaw_starts_deg(const RegistrationConfig& config, std::optional<double> heading_sigma_deg) {
  std::vector<double> out{0.0};
  if (!heading_sigma_deg || !(*heading_sigma_deg > config.yaw_search_min_sigma_deg)) return out;
  const double span = std::min(3.0 * *heading_sigma_deg, config.yaw_search_max_deg);
  for (int k = 1; k * config.yaw_search_step_deg <= span + 1e-9; ++k) {
    out.push_back(-k * config.yaw_search_step_deg);
    out.push_back(k * config.yaw_search_step_deg);
  }
  return out;
}

std::size_t yaw_support(const RegistrationConfig& config, const IcpResult& icp) {
  const double radius = 2.0 * config.min_threshold_m;
  return static_cast<std::size_t>(std::count_if(icp.inliers.begin(), icp.inliers.end(),
                                                [&](const Correspondence& k) { return k.distance <= radius; }));
}

YawSearchResult run_icp_with_yaw_search(const RegistrationConfig& config, const TwinTileIndex& index,
                                        const std::vector<Eigen::Vector3d>& p_W,
                                        const std::vector<Eigen::Matrix3d>& cov_W, const Eigen::Vector3d& pivot_W,
                                        std::optional<double> heading_sigma_deg,
                                        const std::optional<ScalePrior>& scale_prior) {
  const std::vector<double> starts = yaw_starts_deg(config, heading_sigma_deg);
  YawSearchResult out;
  out.starts = static_cast<int>(starts.size());
  std::vector<std::pair<double, std::size_t>> results;  // (final heading offset [deg], support) of every start
  for (const double yaw : starts) {
    const Eigen::Matrix3d dR0 = Eigen::AngleAxisd(yaw * kDegToRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    IcpResult icp = run_icp(config, index, p_W, cov_W, pivot_W, dR0, scale_prior);
    const std::size_t support = icp.converged ? yaw_support(config, icp) : 0;
    results.emplace_back(heading_deg(icp.dR), support);
    // Strictly better only: on a tie the start nearer the estimator's own heading (earlier in the list) stays.
    if (results.size() == 1 || support > out.support) {
      out.icp = std::move(icp);
      out.support = support;
    }
  }
  const double best_heading = heading_deg(out.icp.dR);
  for (const auto& [heading, support] : results) {
    if (wrapped_difference_deg(heading, best_heading) > 0.5 * config.yaw_search_step_deg) {
      out.runner_up = std::max(out.runner_up, support);
    }
  }
  out.ambiguous = out.starts > 1 && out.support > 0 &&
                  static_cast<double>(out.runner_up) >= config.yaw_search_ambiguity * static_cast<double>(out.support);
  return out;
}

}  // namespace twinslam::registration
