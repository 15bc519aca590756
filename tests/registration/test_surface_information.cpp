// The adaptive information with the twin's per-surface error (surface_error_m > 0): inliers are grouped by the plane
// they matched, and the information is the inverse of the covariance the correction really has when every twin
// surface is offset as a whole - checked against the spread of least-squares solutions over many drawn twins.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Cholesky>

#include "plane_correspondences.hpp"
#include "twinslam/geometry/information_order.hpp"
#include "twinslam/registration/information.hpp"

namespace twinslam::registration {
namespace {

using test::plane;  // plane_correspondences.hpp: the keyframe 5-10 m from every plane, as in a street

// A street corner: ground 8 m below, a wall on either side, a facade ahead; four surfaces, every direction observed.
std::vector<Correspondence> street_corner() {
  std::vector<Correspondence> c;
  plane(c, {-10, -10, -8}, {20, 0, 0}, {0, 30, 0});  // ground, normal up
  plane(c, {-6, -10, -8}, {0, 30, 0}, {0, 0, 15});   // wall x = -6, normal +x
  plane(c, {7, -10, -8}, {0, 0, 15}, {0, 30, 0});    // wall x = +7, normal -x
  plane(c, {-10, 20, -8}, {0, 0, 15}, {16, 0, 0});   // facade y = 20
  return c;
}

RegistrationConfig surface_config(double surface_error_m) {
  RegistrationConfig config;
  config.estimate_scale = false;
  config.correlation_inflation = 1.0;  // the per-point noise exactly as drawn below
  config.surface_error_m = surface_error_m;
  return config;
}

TEST(SurfaceInformation, InliersAreGroupedByTheTwinPlaneTheyMatched) {
  std::vector<Correspondence> c = street_corner();
  const std::size_t before_parallel = c.size();
  plane(c, {-10, -10, -7}, {20, 0, 0}, {0, 30, 0});  // a roof 1 m above the ground: parallel, another surface
  const std::vector<int> group = group_surfaces(c, 10.0, 0.3);
  ASSERT_EQ(group.size(), c.size());
  for (std::size_t j = 0; j < c.size(); ++j) EXPECT_EQ(group[j], static_cast<int>(j / 121)) << j;  // 121 per plane
  EXPECT_EQ(group[before_parallel], 4);
  // The two walls face each other: opposite normals, never one surface even with a wide tolerance.
  EXPECT_NE(group_surfaces(c, 89.0, 100.0)[121], group_surfaces(c, 89.0, 100.0)[242]);
}

TEST(SurfaceInformation, WithoutSurfaceErrorItIsTheIndependentNoiseInformation) {
  const std::vector<Correspondence> c = street_corner();
  RegistrationConfig config = surface_config(0.0);
  const Information independent = compute_information(config, c, 0.05, 0.05);
  config.surface_error_m = 1e-9;  // the surface path with a vanishing surface error
  const Information surface = compute_information(config, c, 0.05, 0.05);
  EXPECT_EQ(surface.surfaces, 4);
  EXPECT_NEAR((surface.information - independent.information).norm(), 0.0, 1e-6 * independent.information.norm());
}

// The information must be the inverse covariance of the correction: over drawn twins (each surface offset along its
// normal by N(0, 0.2^2), every point by N(0, 0.05^2)) the least-squares corrections xi give E[xi^T W xi] = 6.
TEST(SurfaceInformation, IsTheInverseCovarianceOfTheCorrectionWhenSurfacesAreOffsetAsAWhole) {
  const std::vector<Correspondence> c = street_corner();
  const double surface_m = 0.2, point_m = 0.05;
  const Information with_surfaces = compute_information(surface_config(surface_m), c, point_m, point_m);
  const Information independent = compute_information(surface_config(0.0), c, point_m, point_m);
  ASSERT_EQ(with_surfaces.zero_directions, 0);
  const Eigen::LLT<Matrix6d> H(with_surfaces.H);
  const std::vector<int> group = group_surfaces(c, 10.0, 0.3);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const int trials = 4000;
  double mean_surface = 0.0, mean_independent = 0.0;
  for (int t = 0; t < trials; ++t) {
    double offset[4];
    for (double& o : offset) o = surface_m * normal(rng);
    Vector6d g = Vector6d::Zero();
    for (std::size_t j = 0; j < c.size(); ++j) {
      Vector6d A;
      A << c[j].a.cross(c[j].n), c[j].n;
      g += A * (offset[group[j]] + point_m * normal(rng));  // the residual of a point of a moved plane
    }
    const Vector6d xi = H.solve(g);  // Gauss-Newton's solution (its sign does not matter here)
    mean_surface += xi.dot(with_surfaces.information * xi) / trials;
    mean_independent += xi.dot(independent.information * xi) / trials;
  }
  EXPECT_NEAR(mean_surface, 6.0, 0.35);  // chi^2(6): the mean of 4000 has a sigma of 0.055
  // Counting 484 points as independent looks claims far more than the twin allows.
  EXPECT_GT(mean_independent, 100.0);
}

TEST(SurfaceInformation, TwoWallsAcrossTheStreetMakeItsCrossingPositionSurerThanOne) {
  std::vector<Correspondence> one_wall;
  plane(one_wall, {-10, -10, -8}, {20, 0, 0}, {0, 30, 0});
  plane(one_wall, {-6, -10, -8}, {0, 30, 0}, {0, 0, 15});
  plane(one_wall, {-10, 20, -8}, {0, 0, 15}, {16, 0, 0});
  const Information one = compute_information(surface_config(0.2), one_wall, 0.01, 0.01);
  const Information two = compute_information(surface_config(0.2), street_corner(), 0.01, 0.01);
  // The predicted position sigma: one surface per direction - the twin's 0.2 m; across the street with two walls the
  // x sigma shrinks (the largest, along y or z, stays at the one facade's / the ground's 0.2 m).
  EXPECT_NEAR(geometry::observed_position_sigma_m(one.information), 0.2, 0.03);
  const auto x_sigma = [](const Information& info) {
    const Matrix6d cov = info.information.inverse();
    return std::sqrt(cov(3, 3));
  };
  EXPECT_LT(x_sigma(two), 0.8 * x_sigma(one));
}

}  // namespace
}  // namespace twinslam::registration
