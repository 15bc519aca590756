// The information's eigen-analysis on ideal geometry: exactly the unobservable directions are found and removed.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "plane_correspondences.hpp"
#include "twinslam/registration/information.hpp"

namespace twinslam::registration {
namespace {

using test::plane;  // plane_correspondences.hpp: the keyframe 5-10 m from every plane, as in a street

Vector6d dir(double wx, double wy, double wz, double vx, double vy, double vz) {
  Vector6d d;
  d << wx, wy, wz, vx, vy, vz;
  return d;
}

Information analyse(const std::vector<Correspondence>& c) {
  RegistrationConfig config;  // adaptive, rigid: eq. (9)'s H (the scale's Schur complement: its own test below)
  config.estimate_scale = false;
  config.surface_error_m = 0.0;  // independent points: H / sigma^2 (the per-surface model: test_surface_information)
  return compute_information(config, c, 0.1, 0.1);
}

void expect_blind_along(const Information& info, const std::vector<Vector6d>& dirs) {
  for (const Vector6d& d : dirs) {
    EXPECT_LT((info.H * d).norm(), 1e-9 * info.H.norm()) << d.transpose();  // H itself has them in its null space
    EXPECT_LT((info.information * d).norm(), 1e-9 * info.information.norm()) << d.transpose();  // ... and W_m too
  }
}

TEST(RegistrationInformation, OnePlaneLeavesThreeDirections) {
  std::vector<Correspondence> c;
  plane(c, {-20, -20, -8}, {40, 0, 0}, {0, 40, 0});  // ground 8 m below the body
  const Information info = analyse(c);
  EXPECT_EQ(info.zero_directions, 3);
  EXPECT_LT(info.eigenvalues.head<3>().cwiseAbs().maxCoeff(), 1e-12);  // ~0 exactly
  EXPECT_GT(info.eigenvalues(3), 0.05);
  expect_blind_along(info, {dir(0, 0, 0, 1, 0, 0), dir(0, 0, 0, 0, 1, 0), dir(0, 0, 1, 0, 0, 0)});
  EXPECT_GT((info.information * dir(0, 0, 0, 0, 0, 1)).norm(), 1.0);  // height stays observed
}

TEST(RegistrationInformation, CorridorOfTwoWallsAndAFloorLeavesOnlyTheAlongCorridorDirection) {
  std::vector<Correspondence> c;
  plane(c, {-5, -30, -6}, {10, 0, 0}, {0, 60, 0});  // floor
  plane(c, {-5, -30, -6}, {0, 60, 0}, {0, 0, 20});  // wall x = -5
  plane(c, {5, -30, -6}, {0, 60, 0}, {0, 0, 20});   // wall x = +5
  const Information info = analyse(c);
  EXPECT_EQ(info.zero_directions, 1);
  EXPECT_LT(std::abs(info.eigenvalues(0)), 1e-12);
  EXPECT_GT(info.eigenvalues(1), 0.01);
  EXPECT_NEAR(std::abs(info.directions.col(0).dot(dir(0, 0, 0, 0, 1, 0))), 1.0, 1e-9);  // the zeroed one is t_y
  expect_blind_along(info, {dir(0, 0, 0, 0, 1, 0)});
}

TEST(RegistrationInformation, CornerOfThreePlanesObservesEverything) {
  std::vector<Correspondence> c;
  plane(c, {-10, -10, -8}, {20, 0, 0}, {0, 20, 0});
  plane(c, {-10, -10, -8}, {0, 20, 0}, {0, 0, 20});
  plane(c, {-10, -10, -8}, {0, 0, 20}, {20, 0, 0});
  const Information info = analyse(c);
  EXPECT_EQ(info.zero_directions, 0);
  EXPECT_GT(info.eigenvalues(0), 0.01);
  EXPECT_NEAR((info.information - info.H / info.sigma_sq).norm(), 0.0, 1e-9 * info.information.norm());
}

TEST(RegistrationInformation, HessianIsIndependentOfWherePointsAreExpressedOnlyThroughThePivot) {
  // H depends on a_j relative to the pivot: shifting every point and the pivot together changes nothing, which is
  // why the correction is linearized about the keyframe position and not about W's origin.
  std::vector<Correspondence> c;
  plane(c, {-10, -10, -8}, {20, 0, 0}, {0, 20, 0});
  plane(c, {-10, -10, -8}, {0, 20, 0}, {0, 0, 20});
  const Matrix6d H = registration_hessian(c);
  EXPECT_NEAR(H(3, 3) + H(4, 4) + H(5, 5), static_cast<double>(c.size()), 1e-9);  // unit normals: tr(sum n n^T) = N
  EXPECT_EQ((H - H.transpose()).norm(), 0.0);
  EXPECT_TRUE(compute_information(RegistrationConfig{}, {}, 0.0, 0.0).information.isZero());
}

// With the scale estimated too (7-DoF ICP), the pose's information is the Schur complement over the log-scale: at
// most the rigid one (their difference is positive semi-definite, rank one), symmetric, and blind where scale and
// position cannot be told apart. Seen from 10 m above one ground plane, a scale about the keyframe moves the plane
// exactly like a vertical translation: t_z is lost. A second plane at another distance (a facade) gives it back.
TEST(RegistrationInformation, EstimatingTheScaleCostsTheInformationItCouplesWith) {
  std::vector<Correspondence> ground;
  plane(ground, {-10, -10, -10}, {20, 0, 0}, {0, 20, 0});
  const Matrix6d rigid = registration_hessian(ground), scaled = registration_hessian(ground, false, true);
  const Eigen::SelfAdjointEigenSolver<Matrix6d> diff(rigid - scaled);
  EXPECT_GT(diff.eigenvalues().minCoeff(), -1e-9 * rigid.norm());
  EXPECT_LT(diff.eigenvalues()(4), 1e-9 * rigid.norm());  // rank one
  EXPECT_EQ((scaled - scaled.transpose()).norm(), 0.0);
  EXPECT_GT(rigid(5, 5), 0.5 * static_cast<double>(ground.size()));
  EXPECT_LT(scaled(5, 5), 1e-9 * rigid(5, 5));  // t_z: gone
  std::vector<Correspondence> two = ground;
  plane(two, {-10, 5, -10}, {20, 0, 0}, {0, 0, 20});  // a facade 5 m away
  EXPECT_GT(registration_hessian(two, false, true)(5, 5), 0.1 * static_cast<double>(ground.size()));
}

}  // namespace
}  // namespace twinslam::registration
