#include "twinslam/geometry/quaternion.hpp"

#include <cmath>

#include "twinslam/geometry/so3.hpp"

namespace twinslam::geometry {

Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const double half = 0.5 * theta;
  // sin(theta/2)/theta -> 1/2 - theta^2/48 for small theta.
  const double k = theta < kSmallAngle ? 0.5 - theta * theta / 48.0 : std::sin(half) / theta;
  Eigen::Quaterniond q(std::cos(half), k * phi.x(), k * phi.y(), k * phi.z());
  return q.normalized();
}

Eigen::Vector3d quaternion_log(const Eigen::Quaterniond& q_in) {
  Eigen::Quaterniond q = canonical(q_in);  // w >= 0 -> angle in [0, pi]
  const double n = q.vec().norm();
  if (n < 1e-12) {
    // theta = 2 atan2(n, w) ~= 2 n / w (w ~= 1 here).
    return 2.0 / q.w() * q.vec();
  }
  const double theta = 2.0 * std::atan2(n, q.w());
  return theta / n * q.vec();
}

Eigen::Quaterniond canonical(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond u = q.normalized();
  if (u.w() < 0.0) u.coeffs() *= -1.0;
  return u;
}

Eigen::Matrix<double, 3, 4> right_perturbation_jacobian(const Eigen::Quaterniond& q) {
  // vec(q^* (x) dq) for unit q = (w, v) and dq = (dw, dv) is  w dv - dw v - v x dv.
  const double norm = q.norm();
  const Eigen::Quaterniond u(q.coeffs() / norm);
  Eigen::Matrix<double, 3, 4> J;
  J.leftCols<3>() = u.w() * Eigen::Matrix3d::Identity() - skew(u.vec());
  J.col(3) = -u.vec();
  // The 1/|q| comes from differentiating q / |q|; the radial part drops out because J * u = 0.
  return (2.0 / norm) * J;
}

}  // namespace twinslam::geometry
