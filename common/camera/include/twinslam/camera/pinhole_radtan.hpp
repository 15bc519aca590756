#pragma once
// Pinhole camera with radial-tangential distortion (OpenCV / EuRoC "radial-tangential", coefficients k1 k2 p1 p2).
// With m = (x, y) = (X/Z, Y/Z) and r^2 = x^2 + y^2 (Brown-Conrady model, as in OpenCV's calib3d documentation):
//   x_d = x (1 + k1 r^2 + k2 r^4) + 2 p1 x y + p2 (r^2 + 2 x^2)
//   y_d = y (1 + k1 r^2 + k2 r^4) + p1 (r^2 + 2 y^2) + 2 p2 x y
//   u = fu x_d + cu,  v = fv y_d + cv
// Unprojection inverts the distortion by Newton's method with the analytic 2x2 Jacobian (quadratic convergence to
// ~1e-15), not OpenCV's fixed-point loop, which stalls at ~1e-6 px near the corners of strongly distorted lenses.
#include "twinslam/camera/camera_model.hpp"

namespace twinslam {

class PinholeRadtan final : public CameraModel {
 public:
  // Throws InputError if the intrinsics are invalid or not of DistortionModel::kRadialTangential.
  explicit PinholeRadtan(const CameraIntrinsics& intrinsics);

  // Largest r^2 = |m|^2 for which the radial part r (1 + k1 r^2 + k2 r^4) still grows (infinity if it always does);
  // beyond it the lens folds the image back onto itself and points would project to two places.
  double max_r2() const { return max_r2_; }

 private:
  ProjectionStatus do_project(const Eigen::Vector3d& p_C, Eigen::Vector2d* uv, Matrix23d* J_uv_p) const override;
  bool do_unproject(const Eigen::Vector2d& uv, Eigen::Vector3d* f_C) const override;
  bool do_distort(const Eigen::Vector2d& m, Eigen::Vector2d* m_d, Eigen::Matrix2d* J_md_m) const override;
  bool do_jacobian_wrt_intrinsics(const Eigen::Vector3d& p_C, Matrix28d* J) const override;

  double max_r2_;
};

}  // namespace twinslam
