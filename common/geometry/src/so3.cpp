#include "twinslam/geometry/so3.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "twinslam/geometry/quaternion.hpp"

namespace twinslam::geometry {

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d W = skew(phi);
  if (theta < kSmallAngle) {
    // exp(W) = I + W + W^2/2 + O(theta^3); the cubic term is below 1e-15 here.
    return Eigen::Matrix3d::Identity() + W + 0.5 * W * W;
  }
  const double s = std::sin(theta) / theta;
  const double c = (1.0 - std::cos(theta)) / (theta * theta);
  return Eigen::Matrix3d::Identity() + s * W + c * W * W;
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& R) {
  return quaternion_log(Eigen::Quaterniond(R));
}

Eigen::Matrix3d so3_right_jacobian(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d W = skew(phi);
  if (theta < kSmallAngle) {
    return Eigen::Matrix3d::Identity() - 0.5 * W + (1.0 / 6.0) * W * W;
  }
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() - (1.0 - std::cos(theta)) / t2 * W +
         (theta - std::sin(theta)) / (t2 * theta) * W * W;
}

Eigen::Matrix3d so3_right_jacobian_inverse(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d W = skew(phi);
  if (theta < kSmallAngle) {
    return Eigen::Matrix3d::Identity() + 0.5 * W + (1.0 / 12.0) * W * W;
  }
  const double t2 = theta * theta;
  // (1 + cos t) / (2 t sin t) written as cot(t/2) / (2t) so it stays finite at t = pi.
  const double half = 0.5 * theta;
  return Eigen::Matrix3d::Identity() + 0.5 * W +
         (1.0 / t2 - std::cos(half) / (2.0 * theta * std::sin(half))) * W * W;
}

Eigen::Matrix3d so3_normalize(const Eigen::Matrix3d& R) {
  // Closest rotation in the Frobenius norm: U V^T from the SVD, with the sign fixed so det = +1.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

double so3_angle_between(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b) {
  return so3_log(R_a.transpose() * R_b).norm();
}

}  // namespace twinslam::geometry
