#pragma once
// Quaternion <-> rotation helpers. Eigen's Quaterniond is a Hamilton quaternion stored [x, y, z, w] in memory, which
// is also the layout of TUM files and of ceres::EigenQuaternionManifold parameter blocks.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::geometry {

// Unit quaternion of Exp(phi), phi the rotation vector [rad]; Taylor series for tiny angles.
Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& phi);

// Rotation vector of a (not necessarily normalized) quaternion, angle in [0, pi]. Uses atan2 of the vector and scalar
// parts, which is well conditioned at every angle (unlike acos(w) near 0 or the matrix trace near pi).
Eigen::Vector3d quaternion_log(const Eigen::Quaterniond& q);

// Normalized quaternion with w >= 0 (q and -q are the same rotation; one sign makes comparisons and files stable).
Eigen::Quaterniond canonical(const Eigen::Quaterniond& q);

// Normalized rotation matrix of a quaternion that may have drifted off the unit sphere.
inline Eigen::Matrix3d rotation_from_quaternion(const Eigen::Quaterniond& q) {
  return q.normalized().toRotationMatrix();
}
inline Eigen::Quaterniond quaternion_from_rotation(const Eigen::Matrix3d& R) { return canonical(Eigen::Quaterniond(R)); }

// Jacobian d(dtheta)/d(q) [3x4, columns in memory order x, y, z, w] of the right (body-frame) perturbation dtheta
// defined by  normalize(q + dq) = q (x) Exp(dtheta)  to first order, i.e. dtheta = 2 vec(q^* (x) dq) / |q|.
// Cost functions compute derivatives w.r.t. dtheta in closed form and multiply by this matrix to obtain the exact
// derivative w.r.t. the four stored coordinates; it is zero along q itself (scaling q does not change the rotation),
// so it is correct for any quaternion manifold Ceres may use.
Eigen::Matrix<double, 3, 4> right_perturbation_jacobian(const Eigen::Quaterniond& q);

}  // namespace twinslam::geometry
