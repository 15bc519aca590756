#pragma once
// SO(3) exponential/logarithm maps and their Jacobians, following the conventions of
// Forster, Carlone, Dellaert, Scaramuzza, "On-Manifold Preintegration for Real-Time Visual-Inertial Odometry",
// IEEE TRO 33(1), 2017, Sec. II ("Preliminaries", SO(3)): Exp(phi) = exp(phi^), phi in R^3 is the rotation vector
// [rad]; the right Jacobian Jr and its inverse satisfy
//   Exp(phi + dphi) ~= Exp(phi) Exp(Jr(phi) dphi)   and   Log(Exp(phi) Exp(dphi)) ~= phi + Jr^-1(phi) dphi.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products and determinants for every user of these maps

namespace twinslam::geometry {

// Below this rotation angle [rad] the closed forms lose precision (1 - cos(theta) cancels), so Taylor series are used.
inline constexpr double kSmallAngle = 1e-5;

// phi^ : the skew-symmetric matrix with skew(a) * b = a x b.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

// (M)^vee: inverse of skew; takes the skew-symmetric part of M so it is meaningful for nearly-skew input.
inline Eigen::Vector3d vee(const Eigen::Matrix3d& m) {
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

// Rodrigues' formula; second-order Taylor expansion below kSmallAngle.
Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi);

// Rotation vector of R with angle in [0, pi]. Goes through a quaternion so it stays accurate near 0 and near pi,
// where the trace-based formula (acos of (tr R - 1) / 2) is ill-conditioned.
Eigen::Vector3d so3_log(const Eigen::Matrix3d& R);

// Right Jacobian Jr(phi) and its inverse (closed forms of Forster Sec. II); Taylor series below kSmallAngle.
Eigen::Matrix3d so3_right_jacobian(const Eigen::Vector3d& phi);
Eigen::Matrix3d so3_right_jacobian_inverse(const Eigen::Vector3d& phi);

// Left Jacobian: Jl(phi) = Jr(-phi), so that Exp(phi + dphi) ~= Exp(Jl(phi) dphi) Exp(phi).
inline Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& phi) { return so3_right_jacobian(-phi); }

// Projects a nearly-orthonormal matrix back onto SO(3) (after long products of rotations accumulate round-off).
Eigen::Matrix3d so3_normalize(const Eigen::Matrix3d& R);

// Geodesic angle between two rotations [rad]: |Log(R_a^T R_b)|.
double so3_angle_between(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b);

}  // namespace twinslam::geometry
