#pragma once
// The estimator's own check of an accepted registration before it becomes a map factor (issue 15). Registration may
// run on another host, be another implementation, be misconfigured or work against a wrong twin: the estimator does
// not fuse what it was told blindly. Two tests, both on the correction about the keyframe,
//   xi = (log dR [rad], dp [m])   (rotation first, in W; dp moves the keyframe body position, as registration's ICP),
// 1. plausibility under the estimator's own uncertainty: xi^T S^-1 xi <= max_mahalanobis_sq, with S the keyframe's
//    covariance published with the LocalMap (LocalMap.T_WB_covariance, same order) plus the floors squared on its
//    diagonal - the quantity registration's own gate computes (registration.cpp), so with registration's defaults
//    (22.46) and a looser bound here the two never disagree; a registration re-admitted by registration's
//    persistence gate (Registration.readmitted: implausible by this test, yet found again and again) skips it;
// 2. size, once the alignment is declared: no correction moves the keyframe more than max_correction_m or turns it
//    more than max_correction_deg (the paper's code bounds 20 m / 15 deg). Before the declaration T_WL is
//    provisional and large corrections are what registration is there to find.
#include <optional>
#include <string>

#include <Eigen/Geometry>

namespace twinslam::estimator {

struct RegistrationGateConfig {
  double max_mahalanobis_sq = 100.0;  // [1] chi^2 with 6 dof; 100 is far beyond registration's 22.46 (99.9 %); 0: off
  double floor_m = 0.1;               // [m] added in quadrature to each position sigma of the published covariance
  double floor_deg = 0.5;             // [deg] ... to each rotation sigma
  double max_correction_m = 15.0;     // [m] keyframe displacement bound once declared; 0: off
  double max_correction_deg = 15.0;   // [deg] rotation bound once declared; 0: off
  void validate() const;              // throws twinslam::InputError naming the field
};

// xi of a correction of W (eq. 3's dT) about the keyframe body position p_WB: (rotation vector, displacement).
Eigen::Matrix<double, 6, 1> correction_about(const Eigen::Isometry3d& correction_W, const Eigen::Vector3d& p_WB);

struct RegistrationGateInput {
  Eigen::Isometry3d correction_W = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();  // the keyframe as published with the LocalMap
  std::optional<Eigen::Matrix<double, 6, 6>> covariance;  // published with it, (rotation, translation); none: no test 1
  bool readmitted = false;  // Registration.readmitted
  bool declared = false;    // the world alignment is declared (test 2 applies)
};

// "" when the registration may be fused, else one line saying which bound it broke and by how much.
std::string registration_refusal(const RegistrationGateConfig& config, const RegistrationGateInput& in);

}  // namespace twinslam::estimator
