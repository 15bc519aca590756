#pragma once
// Online correction of the camera's intrinsic calibration in the sliding window, in bearing space (the estimator sees
// bearings, not pixels). Why: the tracking front end unprojects pixels with the stated intrinsics; a stated focal
// length 0.3 % off, a principal point 1 px off and k1 0.002 off (a checkerboard calibration's residual) bend every
// bearing the same way for the whole flight. The VIO then drifts 0.4-0.5 % of the path on city-loops instead of 0.1 %,
// and the landmark cloud registration fits to the twin is bent, so its corrections are off by about 0.5 m.
//
// The model, on the equidistant plane q = theta u of a bearing f (theta: angle from the optical axis z, u: unit
// direction of (f_x, f_y)), which is where the equidistant (Kannala-Brandt) model is linear in the focal length:
//   q' = (1 + c0 + c1 theta^2) q + (c2, c3),        f' = (sin|q'| q'/|q'|, cos|q'|).
// c0: scale of the angles (a relative focal-length error: stated fu = true fu (1 + c0) to first order), c1 [1/rad^2]:
// the first radial term (k1 stated - true, to first order), (c2, c3) [rad]: the principal point's offset over the
// focal length. For a pinhole lens (x = tan theta) the same four absorb the errors to first order near the axis and the
// k1 term bends the rest. The block is Euclidean (4 values), so the marginalization keeps it like any other block.
#include <array>
#include <memory>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/manifold.h>
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/estimator/reprojection_factor.hpp"

namespace twinslam::estimator {

constexpr int kLensSize = 4;

// f' above for the unit bearing f and the correction c (4 values); dfc_dc (may be null) receives df'/dc (3x4).
Eigen::Vector3d corrected_bearing(const Eigen::Vector3d& f, const double* c,
                                  Eigen::Matrix<double, 3, kLensSize>* dfc_dc = nullptr);

// ReprojectionFactor with the lens correction as a fourth block: [anchor pose 7, observer pose 7, inverse depth 1,
// lens 4]. Both the anchor bearing and the observation pass through corrected_bearing(); the residual is
// s [t1 t2]^T (b - f'_Cj) with the tangent basis of the stated observation (so its Jacobian w.r.t. f'_Cj is exact).
class LensCalibrationFactor final
    : public ceres::SizedCostFunction<2, kPoseSize, kPoseSize, kInverseDepthSize, kLensSize> {
 public:
  LensCalibrationFactor(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_Cj, const Eigen::Isometry3d& T_BC,
                        double sqrt_information);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  // For the outlier test: angle [rad] between prediction and observation, and cheirality, both with the lens c.
  double angular_error(const double* pose_a, const double* pose_j, double rho, const double* c) const;
  bool in_front(const double* pose_a, const double* pose_j, double rho, const double* c) const;

 private:
  ReprojectionFactor corrected(const double* c) const;
  ReprojectionFactor base_;
  Eigen::Isometry3d T_BC_;
  double sqrt_information_;
};

// Prior sigmas of the four values of c: relative focal length, k1 [1/rad^2], principal point over focal [rad] (x, y).
// A sigma of 0 holds that value at 0 (the stated calibration).
std::vector<int> free_lens_components(const std::array<double, kLensSize>& sigmas);
// The calibration prior r_k = c_k / sigma_k over the free values (at least one).
std::unique_ptr<ceres::CostFunction> new_lens_prior(const std::array<double, kLensSize>& sigmas);
// Holds the values whose sigma is 0 constant in the solve (null when all are free).
std::unique_ptr<ceres::Manifold> new_lens_manifold(const std::array<double, kLensSize>& sigmas);

}  // namespace twinslam::estimator
