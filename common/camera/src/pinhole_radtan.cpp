#include "twinslam/camera/pinhole_radtan.hpp"

#include <cmath>
#include <limits>

#include "twinslam/camera/camera_config.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam {
namespace {

constexpr int kMaxNewtonIterations = 30;
constexpr double kStopResidualPx = 1e-12;     // Newton stops here (machine precision is ~1e-13 px)
constexpr double kAcceptResidualPx = 1e-10;   // an unprojection that cannot reach this is reported as failed

// Smallest s = r^2 > 0 with d/dr [r (1 + k1 r^2 + k2 r^4)] = 1 + 3 k1 s + 5 k2 s^2 = 0, or +inf.
double first_fold_r2(double k1, double k2) {
  const double inf = std::numeric_limits<double>::infinity();
  const double a = 5.0 * k2, b = 3.0 * k1;
  if (std::abs(a) < 1e-300) return b < 0.0 ? -1.0 / b : inf;
  const double disc = b * b - 4.0 * a;
  if (disc < 0.0) return inf;  // never zero: the quadratic keeps the sign of its value at 0, which is +1
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));  // stable roots q/a and 1/q
  double best = inf;
  for (double root : {q / a, q != 0.0 ? 1.0 / q : inf}) {
    if (root > 0.0 && root < best) best = root;
  }
  return best;
}

// The distortion polynomial (see header) and its Jacobian, with no domain check.
void distort_raw(const std::array<double, 4>& c, const Eigen::Vector2d& m, Eigen::Vector2d* m_d,
                 Eigen::Matrix2d* J) {
  const double k1 = c[0], k2 = c[1], p1 = c[2], p2 = c[3];
  const double x = m.x(), y = m.y();
  const double xx = x * x, yy = y * y, xy = x * y, r2 = xx + yy;
  const double radial = 1.0 + r2 * (k1 + k2 * r2);
  (*m_d) << x * radial + 2.0 * p1 * xy + p2 * (r2 + 2.0 * xx), y * radial + p1 * (r2 + 2.0 * yy) + 2.0 * p2 * xy;
  if (J) {
    const double dradial = 2.0 * (k1 + 2.0 * k2 * r2);  // d radial / d(r^2) times 2, so d radial/dx = dradial * x
    const double off = dradial * xy + 2.0 * p1 * x + 2.0 * p2 * y;
    (*J) << radial + dradial * xx + 2.0 * p1 * y + 6.0 * p2 * x, off,  //
        off, radial + dradial * yy + 6.0 * p1 * y + 2.0 * p2 * x;
  }
}

}  // namespace

PinholeRadtan::PinholeRadtan(const CameraIntrinsics& intrinsics) : CameraModel(intrinsics) {
  validate(intrinsics, "PinholeRadtan");
  if (intrinsics.distortion != DistortionModel::kRadialTangential) {
    throw InputError("PinholeRadtan: key 'distortion_model': expected radial-tangential");
  }
  max_r2_ = first_fold_r2(intrinsics.coefficients[0], intrinsics.coefficients[1]);
}

bool PinholeRadtan::do_distort(const Eigen::Vector2d& m, Eigen::Vector2d* m_d, Eigen::Matrix2d* J_md_m) const {
  const double r2 = m.squaredNorm();
  if (!(r2 <= max_r2_)) return false;  // also rejects NaN
  distort_raw(intrinsics_.coefficients, m, m_d, J_md_m);
  return true;
}

ProjectionStatus PinholeRadtan::do_project(const Eigen::Vector3d& p_C, Eigen::Vector2d* uv, Matrix23d* J_uv_p) const {
  const double z = p_C.z();
  if (!(z > 0.0)) return ProjectionStatus::kBehindCamera;
  const double iz = 1.0 / z;
  const Eigen::Vector2d m(p_C.x() * iz, p_C.y() * iz);
  Eigen::Vector2d m_d;
  Eigen::Matrix2d J_d;
  if (!do_distort(m, &m_d, J_uv_p ? &J_d : nullptr)) return ProjectionStatus::kOutsideDomain;
  const auto& in = intrinsics_;
  *uv << in.fu * m_d.x() + in.cu, in.fv * m_d.y() + in.cv;
  if (J_uv_p) {
    Matrix23d J_m_p;  // d(x/z, y/z) / d(p_C)
    J_m_p << iz, 0.0, -m.x() * iz, 0.0, iz, -m.y() * iz;
    *J_uv_p = Eigen::Vector2d(in.fu, in.fv).asDiagonal() * (J_d * J_m_p);
  }
  return ProjectionStatus::kOk;
}

bool PinholeRadtan::do_unproject(const Eigen::Vector2d& uv, Eigen::Vector3d* f_C) const {
  const auto& in = intrinsics_;
  const Eigen::Vector2d target((uv.x() - in.cu) / in.fu, (uv.y() - in.cv) / in.fv);
  if (!target.allFinite()) return false;
  // Residual in pixels, so the tolerances mean the same for every focal length.
  auto residual_px = [&](const Eigen::Vector2d& r) { return std::hypot(in.fu * r.x(), in.fv * r.y()); };

  Eigen::Vector2d m = target, m_d;
  Eigen::Matrix2d J;
  distort_raw(in.coefficients, m, &m_d, &J);
  Eigen::Vector2d res = m_d - target;
  double err = residual_px(res);
  for (int it = 0; it < kMaxNewtonIterations && err > kStopResidualPx; ++it) {
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) return false;  // at a fold: no unique inverse here
    const Eigen::Vector2d step(-(J(1, 1) * res.x() - J(0, 1) * res.y()) / det,
                               -(-J(1, 0) * res.x() + J(0, 0) * res.y()) / det);
    // Backtracking keeps Newton from jumping across a fold on strongly distorted lenses; near the solution the full
    // step is always taken, so convergence stays quadratic.
    double alpha = 1.0;
    Eigen::Vector2d m_try, res_try;
    double err_try = err;
    for (int k = 0; k < 30; ++k, alpha *= 0.5) {
      m_try = m + alpha * step;
      distort_raw(in.coefficients, m_try, &m_d, &J);
      res_try = m_d - target;
      err_try = residual_px(res_try);
      if (err_try < err || err_try <= kStopResidualPx) break;
    }
    if (!(err_try < err) && err_try > kStopResidualPx) return false;  // no progress possible
    m = m_try;
    res = res_try;
    err = err_try;
  }
  if (!(err <= kAcceptResidualPx) || !(m.squaredNorm() <= max_r2_)) return false;
  *f_C = Eigen::Vector3d(m.x(), m.y(), 1.0).normalized();
  return true;
}

bool PinholeRadtan::do_jacobian_wrt_intrinsics(const Eigen::Vector3d& p_C, Matrix28d* J) const {
  if (!(p_C.z() > 0.0)) return false;
  const Eigen::Vector2d m = p_C.head<2>() / p_C.z();
  Eigen::Vector2d m_d;
  if (!do_distort(m, &m_d, nullptr)) return false;
  const double x = m.x(), y = m.y(), r2 = m.squaredNorm(), fu = intrinsics_.fu, fv = intrinsics_.fv;
  J->setZero();
  (*J)(0, 0) = m_d.x();
  (*J)(1, 1) = m_d.y();
  (*J)(0, 2) = 1.0;
  (*J)(1, 3) = 1.0;
  // k1, k2, p1, p2 (linear in the coefficients)
  J->block<1, 4>(0, 4) << fu * x * r2, fu * x * r2 * r2, fu * 2.0 * x * y, fu * (r2 + 2.0 * x * x);
  J->block<1, 4>(1, 4) << fv * y * r2, fv * y * r2 * r2, fv * (r2 + 2.0 * y * y), fv * 2.0 * x * y;
  return true;
}

}  // namespace twinslam
