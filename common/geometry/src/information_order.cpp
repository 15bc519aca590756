#include "twinslam/geometry/information_order.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace twinslam::geometry {
namespace {

// P maps a rotation-first vector to a translation-first one: [dp; dtheta] = P [dtheta; dp].
Matrix6d swap_blocks() {
  Matrix6d P = Matrix6d::Zero();
  P.block<3, 3>(0, 3).setIdentity();
  P.block<3, 3>(3, 0).setIdentity();
  return P;
}

}  // namespace

Matrix6d rotation_first_to_translation_first(const Matrix6d& m_rt) {
  const Matrix6d P = swap_blocks();
  return P * m_rt * P.transpose();
}

Matrix6d translation_first_to_rotation_first(const Matrix6d& m_tr) {
  const Matrix6d P = swap_blocks();  // P^-1 = P^T = P
  return P.transpose() * m_tr * P;
}

Eigen::Matrix<double, 6, 1> rotation_first_to_translation_first(const Eigen::Matrix<double, 6, 1>& v_rt) {
  return swap_blocks() * v_rt;
}

Matrix6d from_row_major(const std::array<double, 36>& a) {
  return Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(a.data());
}

std::array<double, 36> to_row_major(const Matrix6d& m) {
  std::array<double, 36> a{};
  Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(a.data()) = m;
  return a;
}

double observed_position_sigma_m(const Matrix6d& information_rt) {
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (information_rt + information_rt.transpose()));
  const double largest = eig.eigenvalues().maxCoeff();
  if (!(largest > 0.0)) return 0.0;
  Eigen::Matrix<double, 6, 1> inverse = Eigen::Matrix<double, 6, 1>::Zero();
  for (int i = 0; i < 6; ++i) {
    if (eig.eigenvalues()(i) > 1e-12 * largest) inverse(i) = 1.0 / eig.eigenvalues()(i);
  }
  const Matrix6d covariance = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
  const Eigen::Matrix3d position = covariance.bottomRightCorner<3, 3>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> p(0.5 * (position + position.transpose()));
  return std::sqrt(std::max(p.eigenvalues().maxCoeff(), 0.0));
}

}  // namespace twinslam::geometry
