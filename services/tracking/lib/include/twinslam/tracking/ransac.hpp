#pragma once
// Outlier rejection on matched unit bearings of two frames (prev, curr). Two models, both on bearings so they work for
// any field of view, including fisheye rays beyond 90 degrees where normalized image coordinates do not exist:
//
// 1. Known rotation (the gyroscope's R_prev_curr_C): 2-point RANSAC for the translation direction (Kneip, Chli,
//    Siegwart, "Robust Real-Time Visual Odometry with a Single Camera and an IMU", BMVC 2011). With the rotation known,
//    the epipolar constraint f_curr^T [t]x R_curr_prev f_prev = 0 becomes t . n = 0 with n = (R_curr_prev f_prev) x
//    f_curr, so two matches fix t = n1 x n2. Two-point samples need ~7 draws at 30 % outliers instead of ~80 for 8
//    points, and pure rotation (t ~ 0, every n ~ 0) degrades gracefully: every match fits.
// 2. Unknown rotation: essential matrix from 8 bearings (linear 8-point on f_curr^T E f_prev = 0, Hartley & Zisserman
//    eq. 11.3 with bearings instead of homogeneous pixels), projected onto the essential manifold (singular values
//    1, 1, 0), in RANSAC.
//
// Residual of a match: the angle [rad] between each bearing and the epipolar plane of the other, the larger of the two:
//   e = |f_curr^T E f_prev| / min(|E f_prev|, |E^T f_curr|)  (sine of the angle; E = [t]x R_curr_prev for model 1).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace twinslam::tracking {

struct RansacOptions {
  double threshold_rad = 2e-3;   // max residual of an inlier [rad]
  double confidence = 0.999;     // stop when an all-inlier sample was drawn with this probability
  int max_iterations = 200;
  std::uint32_t seed = 42;
};

struct RansacResult {
  std::vector<bool> inlier;      // one per match
  int num_inliers = 0;
  int iterations = 0;
  Eigen::Matrix3d E_curr_prev = Eigen::Matrix3d::Zero();  // best model: f_curr^T E f_prev = 0
};

// Model 1. R_prev_curr_C maps camera-frame coordinates at curr to prev (the gyroscope's rotation since prev).
// f_prev[i], f_curr[i] are unit bearings of match i. Fewer than 2 matches: all are inliers.
RansacResult ransac_known_rotation(const std::vector<Eigen::Vector3d>& f_prev,
                                   const std::vector<Eigen::Vector3d>& f_curr, const Eigen::Matrix3d& R_prev_curr_C,
                                   const RansacOptions& options);

// Model 2. Fewer than 8 matches: all are inliers (nothing can be checked).
RansacResult ransac_essential(const std::vector<Eigen::Vector3d>& f_prev, const std::vector<Eigen::Vector3d>& f_curr,
                              const RansacOptions& options);

// The residual above for one match and a model E_curr_prev [rad, as the sine of the angle].
double epipolar_angle(const Eigen::Matrix3d& E_curr_prev, const Eigen::Vector3d& f_prev,
                      const Eigen::Vector3d& f_curr);

}  // namespace twinslam::tracking
