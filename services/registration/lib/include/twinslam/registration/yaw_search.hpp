#pragma once
// ICP from several start headings while the estimator is unsure of its own (its world alignment comes from a few
// seconds of GNSS, or from a hand-set --initial-pose). Measured on city-loops: the GNSS alignment is ~5 deg off when
// declared; point-to-plane ICP from there converges to the right heading only some of the time (a 5 deg rotation
// moves a facade 30 m away by 2.6 m, near the 3 m gate) and otherwise to a nearby minimum with fewer points on the
// twin. Starting also from rotated headings and keeping the result the twin supports best finds the heading, and
// refusing the result when a clearly different heading fits almost as well keeps a repetitive street from fooling it.
#include <optional>
#include <vector>

#include "twinslam/registration/icp.hpp"

namespace twinslam::registration {

struct YawSearchResult {
  IcpResult icp;                  // of the best-supported start
  int starts = 1;                 // ICP runs (1: no search)
  std::size_t support = 0;        // the winner's support (see yaw_support)
  std::size_t runner_up = 0;      // best support among results whose heading differs by more than half a step
  bool ambiguous = false;         // runner_up >= yaw_search_ambiguity * support
};

// Heading offsets [deg] to start ICP from: {0} unless heading_sigma_deg > yaw_search_min_sigma_deg, else 0, +-step,
// +-2 step, ... within +-min(3 sigma, yaw_search_max_deg). Ordered 0 first, then by |offset| (ties: negative first).
std::vector<double> yaw_starts_deg(const RegistrationConfig& config, std::optional<double> heading_sigma_deg);

// Inliers of an ICP result lying within 2 min_threshold_m of their twin point: a score comparable across starts
// (each start's own gate and sigma adapt to how well it fits, so its inlier count alone is not).
std::size_t yaw_support(const RegistrationConfig& config, const IcpResult& icp);

// ICP from each start heading, rotated about the pivot (the keyframe body position). Deterministic.
YawSearchResult run_icp_with_yaw_search(const RegistrationConfig& config, const TwinTileIndex& index,
                                        const std::vector<Eigen::Vector3d>& p_W,
                                        const std::vector<Eigen::Matrix3d>& cov_W, const Eigen::Vector3d& pivot_W,
                                        std::optional<double> heading_sigma_deg,
                                        const std::optional<ScalePrior>& scale_prior = std::nullopt);

}  // namespace twinslam::registration
