#pragma once
// The initial 4-DoF alignment of L to W (paper eq. 11) from pairs of estimated positions p_LB and global positions
// p_WB (GNSS fixes, or registered positions), weighted by each global position's covariance:
//   argmin_{yaw, t} sum_n (p_W^n - Rz(yaw) p_L^n - t)^T C_n^-1 (p_W^n - Rz(yaw) p_L^n - t).
// Closed form (weighted 2-D Procrustes / Umeyama on the horizontal part) as the start, then Gauss-Newton with the full
// covariances; the covariance of [t, yaw] is the inverse of the normal matrix. Declared converged when the heading
// standard deviation falls below a threshold (the convergence test of Boche et al., 2022) and the pairs span enough
// ground. The paper's code uses unit weights and no convergence test. Pure library: the estimator node feeds it.
#include <optional>
#include <vector>

#include <Eigen/Geometry>

namespace twinslam::estimator {

struct WorldAlignerConfig {
  // Heading sigma below which the alignment is used [deg]. Registrations refine T_WL afterwards, so this only has to
  // bring the twin within the ICP gate: 3 deg moves a landmark 30 m away by 1.6 m (gate 3 m).
  double converged_yaw_sigma_deg = 3.0;
  int min_pairs = 10;                    // at least this many pairs [1]
  double min_span_m = 5.0;               // horizontal extent of the p_L's (max distance from their mean) [m]
  unsigned max_pairs = 600;              // oldest dropped beyond this (a long outage re-alignment uses recent ones)
  void validate() const;                 // throws twinslam::InputError naming the field
};

struct AlignmentPair {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  // estimated body position in L [m]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // global body position in W [m]
  Eigen::Matrix3d cov_W = Eigen::Matrix3d::Identity();  // of p_W [m^2], symmetric positive definite
};

struct WorldAlignment4Dof {
  Eigen::Isometry3d T_WL = Eigen::Isometry3d::Identity();
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();  // of [p_WL (3), yaw_WL] [m^2, rad^2]
  double yaw_sigma_deg = 0.0;
  double span_m = 0.0;
  std::size_t pairs = 0;
  bool converged = false;  // the criteria of the config hold
};

class WorldAligner {
 public:
  explicit WorldAligner(const WorldAlignerConfig& config = {});
  // Throws InputError for a non-finite pair or a covariance that is not positive definite.
  void add(const AlignmentPair& pair);
  void clear() { pairs_.clear(); }
  std::size_t size() const { return pairs_.size(); }
  // nullopt with fewer than 3 pairs (yaw undetermined).
  std::optional<WorldAlignment4Dof> solve() const;

 private:
  WorldAlignerConfig config_;
  std::vector<AlignmentPair> pairs_;
};

}  // namespace twinslam::estimator
