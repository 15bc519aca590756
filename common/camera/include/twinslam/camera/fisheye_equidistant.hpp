#pragma once
// Fisheye camera, equidistant projection with Kannala-Brandt polynomial distortion (OpenCV fisheye / Kalibr
// "equidistant", coefficients k1..k4). With theta the angle between the ray and the optical axis (Kannala & Brandt,
// PAMI 2006, eq. 6, truncated to 4 coefficients as in OpenCV):
//   theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8)
//   (u, v) = (fu theta_d x / r + cu, fv theta_d y / r + cv),  r = sqrt(x^2 + y^2)
// theta = atan2(r, z) is used instead of OpenCV's atan(r / z) so rays beyond 90 degrees (z < 0) are valid: the model
// covers fields of view beyond 180 degrees. Unprojection solves theta_d(theta) = |m_d| by safeguarded Newton.
#include "twinslam/camera/camera_model.hpp"

namespace twinslam {

class FisheyeEquidistant final : public CameraModel {
 public:
  // Throws InputError if the intrinsics are invalid or not of DistortionModel::kEquidistant.
  explicit FisheyeEquidistant(const CameraIntrinsics& intrinsics);

  // Largest angle from the optical axis (rad, <= pi) up to which theta_d(theta) is increasing, i.e. half the widest
  // field of view the polynomial can represent one-to-one.
  double max_theta() const { return max_theta_; }

  // theta_d(theta) and d theta_d / d theta.
  double theta_d(double theta, double* dtheta_d = nullptr) const;

 private:
  ProjectionStatus do_project(const Eigen::Vector3d& p_C, Eigen::Vector2d* uv, Matrix23d* J_uv_p) const override;
  bool do_unproject(const Eigen::Vector2d& uv, Eigen::Vector3d* f_C) const override;
  bool do_distort(const Eigen::Vector2d& m, Eigen::Vector2d* m_d, Eigen::Matrix2d* J_md_m) const override;
  bool do_jacobian_wrt_intrinsics(const Eigen::Vector3d& p_C, Matrix28d* J) const override;

  double max_theta_;
  double max_theta_d_;
};

}  // namespace twinslam
