// 6x6 information between the wire order (rotation, translation) and the estimator's tangent order (translation,
// rotation): round trips are exact and each block lands where its meaning says.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "twinslam/geometry/information_order.hpp"

namespace twinslam::geometry {
namespace {

Matrix6d random_information(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n;
  Matrix6d A;
  for (int i = 0; i < 36; ++i) A.data()[i] = n(rng);
  return A * A.transpose();
}

TEST(InformationOrder, RoundTripBetweenWireAndTangentIsExact) {
  for (unsigned seed = 0; seed < 5; ++seed) {
    const Matrix6d wire = random_information(seed);
    const Matrix6d tangent = rotation_first_to_translation_first(wire);
    EXPECT_EQ(translation_first_to_rotation_first(tangent), wire);
    EXPECT_EQ(from_row_major(to_row_major(wire)), wire);
    // Not the identity map: a generic information changes.
    EXPECT_GT((tangent - wire).norm(), 1e-3);
  }
}

TEST(InformationOrder, RotationOnlyInformationLandsOnTheRotationBlock) {
  // On the wire: information only on roll/pitch/yaw (the first three), e.g. a registration that fixes the heading
  // but not the position.
  Matrix6d wire = Matrix6d::Zero();
  wire.topLeftCorner<3, 3>() << 4, 1, 0, 1, 5, 0, 0, 0, 9;
  const Matrix6d tangent = rotation_first_to_translation_first(wire);
  const Eigen::Matrix3d dp_block = tangent.topLeftCorner<3, 3>();
  const Eigen::Matrix3d dtheta_block = tangent.bottomRightCorner<3, 3>();
  const Eigen::Matrix3d cross_block = tangent.topRightCorner<3, 3>();
  EXPECT_EQ(dp_block, Eigen::Matrix3d::Zero());  // dp block: nothing
  EXPECT_EQ(dtheta_block, Eigen::Matrix3d(wire.topLeftCorner<3, 3>()));  // dtheta block: all of it
  EXPECT_EQ(cross_block, Eigen::Matrix3d::Zero());
  // And a vector: [droll, dpitch, dyaw, dx, dy, dz] -> [dx, dy, dz, droll, dpitch, dyaw].
  Eigen::Matrix<double, 6, 1> v_rt;
  v_rt << 1, 2, 3, 4, 5, 6;
  Eigen::Matrix<double, 6, 1> expected;
  expected << 4, 5, 6, 1, 2, 3;
  EXPECT_EQ(rotation_first_to_translation_first(v_rt), expected);
}

TEST(InformationOrder, RowMajorMatchesTheIdlLayout) {
  std::array<double, 36> a{};
  a[1] = 7.0;  // row 0, column 1
  a[6] = 3.0;  // row 1, column 0
  const Matrix6d m = from_row_major(a);
  EXPECT_EQ(m(0, 1), 7.0);
  EXPECT_EQ(m(1, 0), 3.0);
}

TEST(InformationOrder, ObservedPositionSigmaIsTheLargestPositionSigmaAlongObservedDirections) {
  Matrix6d wire = Matrix6d::Zero();
  EXPECT_EQ(observed_position_sigma_m(wire), 0.0);  // nothing observed: no claim
  // Full rank: 0.1 m along x, 0.5 m along y, 0.2 m along z, rotations 1e-4 rad^2.
  wire.diagonal() << 1e4, 1e4, 1e4, 100.0, 4.0, 25.0;
  EXPECT_NEAR(observed_position_sigma_m(wire), 0.5, 1e-12);
  // One facade: only x observed (and rotation); y and z unobserved say nothing, the sigma is x's.
  wire.diagonal() << 1e4, 1e4, 1e4, 100.0, 0.0, 0.0;
  EXPECT_NEAR(observed_position_sigma_m(wire), 0.1, 1e-12);
  // Rotation coupled with translation: the pseudo-inverse, not the inverse of the position block alone.
  const Matrix6d full = random_information(3);
  const Eigen::Matrix3d position = full.inverse().bottomRightCorner<3, 3>();
  const double expected = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(position).eigenvalues().maxCoeff());
  EXPECT_NEAR(observed_position_sigma_m(full), expected, 1e-9 * expected);
}

}  // namespace
}  // namespace twinslam::geometry
