#include "twinslam/camera/fisheye_equidistant.hpp"

#include <cmath>
#include <numbers>

#include "twinslam/camera/camera_config.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam {
namespace {

constexpr int kMaxNewtonIterations = 100;  // safeguarded: bisection steps make up for bad Newton steps
constexpr double kAcceptResidualPx = 1e-10;

}  // namespace

double FisheyeEquidistant::theta_d(double theta, double* dtheta_d) const {
  const auto& k = intrinsics_.coefficients;
  const double t2 = theta * theta;
  // Horner in theta^2: theta (1 + k1 t2 + k2 t2^2 + k3 t2^3 + k4 t2^4)
  const double poly = 1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])));
  if (dtheta_d) *dtheta_d = 1.0 + t2 * (3.0 * k[0] + t2 * (5.0 * k[1] + t2 * (7.0 * k[2] + t2 * 9.0 * k[3])));
  return theta * poly;
}

FisheyeEquidistant::FisheyeEquidistant(const CameraIntrinsics& intrinsics) : CameraModel(intrinsics) {
  validate(intrinsics, "FisheyeEquidistant");
  if (intrinsics.distortion != DistortionModel::kEquidistant) {
    throw InputError("FisheyeEquidistant: key 'distortion_model': expected equidistant");
  }
  // The domain ends where theta_d stops increasing (first zero of its derivative) or at pi. A fine scan finds the
  // first sign change of a degree-8 polynomial (which may have several roots); bisection then pins it down.
  const double pi = std::numbers::pi;
  constexpr int kSteps = 4096;
  max_theta_ = pi;
  double prev = 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    const double t = pi * i / kSteps;
    double d = 0.0;
    theta_d(t, &d);
    if (d <= 0.0) {
      double lo = prev, hi = t;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        theta_d(mid, &d);
        (d > 0.0 ? lo : hi) = mid;
      }
      max_theta_ = lo;
      break;
    }
    prev = t;
  }
  max_theta_d_ = theta_d(max_theta_);
}

ProjectionStatus FisheyeEquidistant::do_project(const Eigen::Vector3d& p_C, Eigen::Vector2d* uv,
                                             Matrix23d* J_uv_p) const {
  const double x = p_C.x(), y = p_C.y(), z = p_C.z();
  const double r = std::hypot(x, y);
  if (!std::isfinite(r) || !std::isfinite(z)) return ProjectionStatus::kOutsideDomain;
  // On the optical axis behind the camera (theta = pi) the azimuth is undefined; the zero vector has no direction.
  if (r == 0.0 && !(z > 0.0)) return ProjectionStatus::kOutsideDomain;
  const double theta = std::atan2(r, z);
  if (theta > max_theta_) return ProjectionStatus::kOutsideDomain;
  double dtd = 0.0;
  const double td = theta_d(theta, &dtd);
  // (u, v) = (fu s x + cu, fv s y + cv) with s = theta_d / r; on the axis s -> theta_d'(0) dtheta/dr = 1 / z.
  const double s = r > 0.0 ? td / r : 1.0 / z;
  const auto& in = intrinsics_;
  *uv << in.fu * s * x + in.cu, in.fv * s * y + in.cv;
  if (J_uv_p) {
    Eigen::RowVector3d grad_s;  // d s / d(x, y, z)
    const double rho2 = r * r + z * z;
    if (r > 0.0) {
      // theta = atan2(r, z): dtheta/dr = z / rho2, dtheta/dz = -r / rho2.
      const double ds_dr = (dtd * z / rho2 - s) / r;
      grad_s << ds_dr * x / r, ds_dr * y / r, -dtd / rho2;
    } else {
      grad_s << 0.0, 0.0, -1.0 / (z * z);  // s is even in r, so ds/dr = 0 on the axis
    }
    J_uv_p->row(0) = in.fu * (Eigen::RowVector3d(s, 0.0, 0.0) + x * grad_s);
    J_uv_p->row(1) = in.fv * (Eigen::RowVector3d(0.0, s, 0.0) + y * grad_s);
  }
  return ProjectionStatus::kOk;
}

bool FisheyeEquidistant::do_unproject(const Eigen::Vector2d& uv, Eigen::Vector3d* f_C) const {
  const auto& in = intrinsics_;
  const Eigen::Vector2d m_d((uv.x() - in.cu) / in.fu, (uv.y() - in.cv) / in.fv);
  const double td = m_d.norm();
  if (!std::isfinite(td) || td > max_theta_d_) return false;
  if (td == 0.0) {
    *f_C = Eigen::Vector3d::UnitZ();
    return true;
  }
  // Solve theta_d(theta) = td on [0, max_theta], where theta_d is increasing: Newton inside a shrinking bracket,
  // falling back to bisection whenever a Newton step would leave it.
  double lo = 0.0, hi = max_theta_, theta = std::min(td, max_theta_);
  for (int it = 0; it < kMaxNewtonIterations; ++it) {
    double d = 0.0;
    const double f = theta_d(theta, &d) - td;
    if (f == 0.0) break;
    (f > 0.0 ? hi : lo) = theta;
    double next = theta - f / d;
    if (!(d > 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - theta) <= 1e-16 * (1.0 + theta)) {
      theta = next;
      break;
    }
    theta = next;
  }
  if (!(std::abs(theta_d(theta) - td) * std::max(in.fu, in.fv) <= kAcceptResidualPx)) return false;
  const double sin_over_td = std::sin(theta) / td;
  *f_C << sin_over_td * m_d.x(), sin_over_td * m_d.y(), std::cos(theta);
  return true;
}

bool FisheyeEquidistant::do_distort(const Eigen::Vector2d& m, Eigen::Vector2d* m_d, Eigen::Matrix2d* J_md_m) const {
  // m = (x/z, y/z) exists only for z > 0, so here theta = atan(r) < pi/2 (OpenCV's fisheye::distortPoints).
  const double r = m.norm();
  if (!std::isfinite(r)) return false;
  const double theta = std::atan(r);
  if (theta > max_theta_) return false;
  double dtd = 0.0;
  const double td = theta_d(theta, &dtd);
  const double s = r > 0.0 ? td / r : 1.0;
  *m_d = s * m;
  if (J_md_m) {
    J_md_m->setIdentity();
    *J_md_m *= s;
    if (r > 0.0) {
      const double ds_dr = (dtd / (1.0 + r * r) - s) / r;  // dtheta/dr = 1 / (1 + r^2)
      *J_md_m += (ds_dr / r) * m * m.transpose();
    }
  }
  return true;
}

bool FisheyeEquidistant::do_jacobian_wrt_intrinsics(const Eigen::Vector3d& p_C, Matrix28d* J) const {
  Eigen::Vector2d uv;
  if (do_project(p_C, &uv, nullptr) != ProjectionStatus::kOk) return false;
  const double x = p_C.x(), y = p_C.y(), z = p_C.z(), r = std::hypot(x, y);
  const double theta = std::atan2(r, z);
  const double s = r > 0.0 ? theta_d(theta) / r : 1.0 / z;
  const auto& in = intrinsics_;
  J->setZero();
  (*J)(0, 0) = s * x;
  (*J)(1, 1) = s * y;
  (*J)(0, 2) = 1.0;
  (*J)(1, 3) = 1.0;
  if (r > 0.0) {  // d theta_d / d k_i = theta^(2i+3) for i = 0..3; all vanish on the axis
    double t_pow = theta * theta * theta;
    for (int i = 0; i < 4; ++i, t_pow *= theta * theta) {
      (*J)(0, 4 + i) = in.fu * x / r * t_pow;
      (*J)(1, 4 + i) = in.fv * y / r * t_pow;
    }
  }
  return true;
}

}  // namespace twinslam
