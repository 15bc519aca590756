#pragma once
// Camera models shared by the simulator (renders images with them), the tracking service (pixels <-> bearings) and the
// estimator (reprojection residuals and their Jacobians). All maps go between a point p_C in the camera frame C
// (x right, y down, z forward, metres or any scale) and a pixel (u, v) in px with the origin at the centre of the
// top-left pixel (OpenCV / EuRoC convention).
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string_view>

namespace twinslam {

// Lens distortion families we read from EuRoC/Kalibr `sensor.yaml` (`camera_model: pinhole` for both).
enum class DistortionModel {
  kRadialTangential,  // OpenCV "plumb bob" without k3: coefficients k1 k2 p1 p2
  kEquidistant,       // Kannala-Brandt / OpenCV fisheye: coefficients k1 k2 k3 k4
};

std::string_view to_string(DistortionModel model);

// Everything a camera model needs; the extrinsics and rate live in CameraConfig (camera_config.hpp).
struct CameraIntrinsics {
  DistortionModel distortion = DistortionModel::kRadialTangential;
  int width = 640;                                // px
  int height = 400;                               // px
  double fu = 400.0, fv = 400.0;                  // focal lengths, px
  double cu = 319.5, cv = 199.5;                  // principal point, px
  std::array<double, 4> coefficients{0, 0, 0, 0};  // meaning depends on `distortion` (see above)
};

enum class ProjectionStatus {
  kOk,
  kBehindCamera,   // the pinhole model cannot image a point with z <= 0
  kOutsideDomain,  // beyond the angle/radius where the distortion polynomial is still one-to-one
};

using Matrix23d = Eigen::Matrix<double, 2, 3>;
// d(u, v) / d(fu, fv, cu, cv, c0, c1, c2, c3): for online calibration in the estimator.
using Matrix28d = Eigen::Matrix<double, 2, 8>;

class CameraModel {
 public:
  virtual ~CameraModel() = default;

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  int width() const { return intrinsics_.width; }
  int height() const { return intrinsics_.height; }

  // p_C -> pixel. The pixel is written for every kOk result, also when it falls outside the image (use in_image).
  // J_uv_p (optional) = d(u, v) / d(p_C), analytic, in px per unit of p_C.
  ProjectionStatus project(const Eigen::Vector3d& p_C, Eigen::Vector2d* uv, Matrix23d* J_uv_p = nullptr) const {
    return do_project(p_C, uv, J_uv_p);
  }

  // Pixel -> unit bearing f_C. False if the pixel lies outside the model's domain (no ray maps there).
  bool unproject(const Eigen::Vector2d& uv, Eigen::Vector3d* f_C) const { return do_unproject(uv, f_C); }

  // The lens distortion alone, on normalized pinhole coordinates m = (x/z, y/z) of a point in front of the camera:
  // m -> m_d with pixel = (fu m_d.x + cu, fv m_d.y + cv). J_md_m (optional) = d(m_d) / d(m), 2x2.
  // False outside the model's domain. Trackers use it to move between distorted and undistorted image planes.
  bool distort(const Eigen::Vector2d& m, Eigen::Vector2d* m_d, Eigen::Matrix2d* J_md_m = nullptr) const {
    return do_distort(m, m_d, J_md_m);
  }

  // d(u, v) / d(fu, fv, cu, cv, coefficients[0..3]) at p_C; false where project() is not kOk.
  bool jacobian_wrt_intrinsics(const Eigen::Vector3d& p_C, Matrix28d* J) const {
    return do_jacobian_wrt_intrinsics(p_C, J);
  }

  // True if uv lies at least `border` px inside the image (pixel centres span [0, width-1] x [0, height-1]).
  bool in_image(const Eigen::Vector2d& uv, double border = 0.0) const {
    return uv.x() >= border && uv.y() >= border && uv.x() <= width() - 1.0 - border &&
           uv.y() <= height() - 1.0 - border;
  }

 protected:
  explicit CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {}
  // The models implement these (non-virtual interface: default arguments live only in the public wrappers).
  virtual ProjectionStatus do_project(const Eigen::Vector3d& p_C, Eigen::Vector2d* uv, Matrix23d* J_uv_p) const = 0;
  virtual bool do_unproject(const Eigen::Vector2d& uv, Eigen::Vector3d* f_C) const = 0;
  virtual bool do_distort(const Eigen::Vector2d& m, Eigen::Vector2d* m_d, Eigen::Matrix2d* J_md_m) const = 0;
  virtual bool do_jacobian_wrt_intrinsics(const Eigen::Vector3d& p_C, Matrix28d* J) const = 0;

  CameraIntrinsics intrinsics_;
};

// Builds the model named by intrinsics.distortion; throws InputError if the intrinsics are invalid.
std::unique_ptr<CameraModel> make_camera(const CameraIntrinsics& intrinsics);

}  // namespace twinslam
