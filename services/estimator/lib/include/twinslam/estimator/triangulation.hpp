#pragma once
// Triangulation of a landmark from unit bearings observed at several keyframes, returning the anchored inverse depth
// of landmark.hpp.
//
// 1. Linear: the multi-view midpoint, the point minimizing the sum of squared distances to the rays (c_i, d_i) in L:
//      sum_i (I - d_i d_i^T) x = sum_i (I - d_i d_i^T) c_i
//    (the midpoint method of Hartley & Sturm, "Triangulation", CVIU 1997, for two views; Lee & Civera, "Triangulation: why optimize?", BMVC 2019,
//    for the generalization). It works on bearings, so fisheye rays beyond 90 deg are no special case.
// 2. Gauss-Newton on the inverse depth rho along the anchor bearing, minimizing the same tangent-plane bearing errors as
//    ReprojectionFactor (the anchor observation is exact by construction). With the anchor fixed the prediction in
//    camera i is linear in rho,  h_i(rho) = R_CiL R_LCa f_Ca + rho R_CiL (c_a - c_i)  (rho p_Ci, c = camera centres),
//    so each iteration is a scalar solve.
// 3. Checks: parallax, cheirality in every view, depth range and the reprojection error of every observation.
#include <cstddef>
#include <span>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::estimator {

struct TriangulationConfig {
  // Largest angle between the anchor ray and another ray, both in L, so rotation is compensated [deg]. Below about a
  // degree the depth is mostly noise (1 px at f = 460 is 0.12 deg).
  double min_parallax_deg = 1.0;
  double max_error_px = 3.0;     // reprojection error allowed in every view [px] (angle times focal_px)
  double focal_px = 460.0;       // px per radian, to express angles in px
  double min_depth_m = 0.1;      // along the anchor bearing [m]
  double max_depth_m = 1000.0;   // [m]
  int max_iterations = 10;       // Gauss-Newton iterations on rho

  void validate() const;  // throws twinslam::InputError naming the bad field
};

// One observation: the pose T_LB of the observing keyframe and the unit bearing of the landmark in its camera.
struct BearingObservation {
  Eigen::Isometry3d T_LB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d f_C = Eigen::Vector3d::UnitZ();
};

enum class TriangulationStatus {
  kOk,
  kTooFewViews,      // fewer than two observations
  kLowParallax,      // rays almost parallel: the depth is not determined
  kBehindCamera,     // the point lies behind at least one observing camera
  kDepthOutOfRange,  // outside [min_depth_m, max_depth_m] in the anchor
  kLargeError,       // some observation is farther than max_error_px from the triangulated point
};
std::string_view to_string(TriangulationStatus status);

struct TriangulationResult {
  TriangulationStatus status = TriangulationStatus::kTooFewViews;
  double rho = 0.0;                                 // inverse depth along the anchor bearing [1/m]
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();    // the point in L [m] (valid when rho > 0)
  double parallax_deg = 0.0;                        // as in TriangulationConfig::min_parallax_deg
  double max_error_px = 0.0;                        // largest reprojection error over the observations [px]
  bool ok() const { return status == TriangulationStatus::kOk; }
};

// Triangulates from `observations` (>= 2), anchored at observations[anchor] (whose bearing becomes f_Ca). T_BC is the
// camera in the body. The result carries the values computed up to the failing check.
TriangulationResult triangulate(const TriangulationConfig& config, std::span<const BearingObservation> observations,
                                const Eigen::Isometry3d& T_BC, std::size_t anchor = 0);

}  // namespace twinslam::estimator
