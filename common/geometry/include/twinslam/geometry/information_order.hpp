#pragma once
// Orders of 6-vectors and 6x6 matrices at the boundaries (docs/ARCHITECTURE.md, "Orders at the boundaries"):
//  - on the wire (IDL `Registration.information`, row-major double[36]): (rotation, translation) = [dtheta, dp];
//  - in the estimator (pose block tangent, imu_state.hpp / marginalization.hpp): (translation, rotation) = [dp, dtheta].
// The permutation swaps the two 3-blocks; it is its own inverse, but the two names say which way a call goes.
// Frames are not changed here (where the rotation acts and in which frame the translation is expressed is the
// caller's, see the Registration message).
#include <array>

#include <Eigen/Core>

namespace twinslam::geometry {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// [dtheta, dp] ordered -> [dp, dtheta] ordered (for vectors: the same swap).
Matrix6d rotation_first_to_translation_first(const Matrix6d& m_rt);
Matrix6d translation_first_to_rotation_first(const Matrix6d& m_tr);
Eigen::Matrix<double, 6, 1> rotation_first_to_translation_first(const Eigen::Matrix<double, 6, 1>& v_rt);

// Row-major double[36] (the IDL layout) <-> matrix. from_row_major does not symmetrize or check.
Matrix6d from_row_major(const std::array<double, 36>& a);
std::array<double, 36> to_row_major(const Matrix6d& m);

// The largest position sigma [m] that a (rotation, translation)-ordered information states along the directions it
// observes: sqrt of the largest eigenvalue of the translation block of its pseudo-inverse (eigenvalues below 1e-12 x
// the largest count as unobserved, so a rank-deficient registration says nothing along those). 0 for a zero matrix.
double observed_position_sigma_m(const Matrix6d& information_rt);

}  // namespace twinslam::geometry
