#pragma once
// The source cloud of eq. (2): the estimator's sparse landmarks of one keyframe, cleaned and expressed in W with the
// current guess T_WL (a_j before the correction). Steps: drop low-quality landmarks, voxel downsampling (one
// centroid per voxel, so dense clusters on textured patches do not outweigh the rest of the view), statistical
// outlier removal (badly triangulated points float away from their neighbours): PCL StatisticalOutlierRemoval's
// definition on the library's own KD-tree — PCL's filter spent 1.2 ms of a keyframe's 1.5 ms preprocessing in its
// search wrapper (bench_registration); test_registration_pcl checks that both keep the same points.
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/registration/registration_config.hpp"

namespace twinslam::registration {

struct Landmark {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  // position in the estimator's local frame L [m]
  double quality = 1.0;                           // the estimator's confidence in [0, 1]
  Eigen::Matrix3d cov_L = Eigen::Matrix3d::Zero();  // covariance of p_L [m^2] (LocalMap v2); zero: unknown
};

// What the estimator hands over for one keyframe.
struct SourceInput {
  std::vector<Landmark> landmarks;
  Eigen::Isometry3d T_WL = Eigen::Isometry3d::Identity();  // current guess of L in W (maps p_L to p_W)
  Eigen::Isometry3d T_LB = Eigen::Isometry3d::Identity();  // the keyframe's body pose in L
};

struct SourceCloud {
  std::vector<Eigen::Vector3d> p_W;                // preprocessed landmarks in W with the guess: p_W = T_WL p_L [m]
  std::vector<Eigen::Matrix3d> cov_W;              // ... their covariances in W [m^2] (a voxel's: of its centroid)
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();  // keyframe body position in W (T_WL T_LB): ICP's pivot [m]
  std::size_t input = 0, after_quality = 0, after_voxel = 0;  // counts after each step (p_W.size() is the last)
};

// Indices (ascending) of the points whose mean distance to their `neighbors` nearest others is at most
// mean + stddev_mul * stddev over the cloud (PCL StatisticalOutlierRemoval, setMeanK / setStddevMulThresh). Points are
// taken relative to `origin` in float, as PCL would hold them. neighbors in [1, 32]; fewer points than that: all kept.
// The neighbour searches run on `threads` threads; the result does not depend on it.
std::vector<std::size_t> statistical_inliers(const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& origin,
                                             int neighbors, double stddev_mul, int threads = 1);

// Throws InputError for a non-finite landmark or pose, a quality outside [0, 1] or a covariance that is not finite,
// symmetric and of non-negative diagonal (naming the landmark index).
// Deterministic: the output order depends only on the input.
SourceCloud preprocess(const RegistrationConfig& config, const SourceInput& input);

}  // namespace twinslam::registration
