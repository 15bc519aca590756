// ReprojectionFactor on unit bearings: analytic vs numeric Jacobians (pinhole-like and > 90 deg bearings), zero
// residual at the truth, pixel-equivalent scaling, the anchor's own observation, cheirality.
#include <cmath>
#include <memory>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"
#include "twinslam/geometry/so3.hpp"
#include "vision_test_utils.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

constexpr double kPi = 3.14159265358979323846;

// One landmark seen from an anchor and an observer. `off_axis_deg` is the angle of the point from the observer's
// optical axis: < 40 deg is what a pinhole sees, > 90 deg only a fisheye.
struct Scene {
  double pose_a[7], pose_j[7], rho;
  Eigen::Vector3d f_Ca, f_Cj;
  Eigen::Isometry3d T_BC = ts::forward_camera_T_BC();

  Scene(std::mt19937& rng, double off_axis_deg) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Eigen::Isometry3d T_LBj = ts::random_pose(rng);
    const double polar = off_axis_deg * kPi / 180.0, azimuth = 2 * kPi * u(rng), depth = 2.0 + 20.0 * u(rng);
    const Eigen::Vector3d p_Cj =
        depth * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                                std::cos(polar));
    const Eigen::Vector3d p_L = T_LBj * T_BC * p_Cj;
    // The anchor a metre or so away, rotated by a few tenths of a radian, so the point has parallax.
    Eigen::Isometry3d T_LBa = T_LBj;
    T_LBa.translation() += ts::random_vector(rng, 1.0);
    T_LBa.linear() = T_LBj.linear() * tg::so3_exp(ts::random_vector(rng, 0.3));
    const Eigen::Vector3d p_Ca = (T_LBa * T_BC).inverse() * p_L;
    f_Ca = p_Ca.normalized();
    rho = 1.0 / p_Ca.norm();
    f_Cj = p_Cj.normalized();
    ts::pack_pose(T_LBa, pose_a);
    ts::pack_pose(T_LBj, pose_j);
  }
  std::vector<double*> params() { return {pose_a, pose_j, &rho}; }
};

double random_off_axis(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

void expect_jacobians_match(double lo_deg, double hi_deg, unsigned seed) {
  std::mt19937 rng(seed);
  double worst = 0.0;
  for (int trial = 0; trial < 30; ++trial) {
    Scene s(rng, random_off_axis(rng, lo_deg, hi_deg));
    // Evaluate away from the truth: a state error of centimetres and ~1 deg, and an off-by-a-bit observation.
    const Eigen::Vector3d observed = (s.f_Cj + ts::random_vector(rng, 0.01)).normalized();
    for (int k = 0; k < 3; ++k) s.pose_j[k] += 0.05 * ts::random_vector(rng, 1.0)[k];
    Eigen::Map<Eigen::Vector4d>(s.pose_j + 3) =
        (Eigen::Map<Eigen::Quaterniond>(s.pose_j + 3) * tg::quaternion_exp(ts::random_vector(rng, 0.02))).coeffs();
    s.rho *= 1.1;
    const est::ReprojectionFactor factor(s.f_Ca, observed, s.T_BC, 460.0);
    const auto analytic = ts::analytic_jacobians(factor, s.params());
    const auto numeric = ts::numeric_jacobians(factor, s.params());
    for (int b = 0; b < 3; ++b) {
      const double err = ts::max_relative_error(analytic[b], numeric[b]);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-6) << "trial " << trial << " block " << b << "\nanalytic\n"
                           << analytic[b] << "\nnumeric\n"
                           << numeric[b];
    }
  }
  std::ostringstream text;
  text << std::scientific << worst;
  ::testing::Test::RecordProperty("worst_relative_error", text.str());
}

}  // namespace

TEST(ReprojectionFactor, AnalyticJacobiansMatchNumericForPinholeLikeBearings) { expect_jacobians_match(0, 40, 11); }

TEST(ReprojectionFactor, AnalyticJacobiansMatchNumericBeyondNinetyDegrees) { expect_jacobians_match(95, 130, 12); }

TEST(ReprojectionFactor, ResidualVanishesAtTheTrueState) {
  std::mt19937 rng(13);
  for (double off_axis : {0.0, 30.0, 100.0}) {
    Scene s(rng, off_axis);
    const est::ReprojectionFactor factor(s.f_Ca, s.f_Cj, s.T_BC, 460.0);
    Eigen::Vector2d r;
    const double* p[3] = {s.pose_a, s.pose_j, &s.rho};
    ASSERT_TRUE(factor.Evaluate(p, r.data(), nullptr));
    EXPECT_LT(r.norm(), 1e-9) << off_axis;
    EXPECT_TRUE(factor.in_front(s.pose_a, s.pose_j, s.rho));
  }
}

TEST(ReprojectionFactor, ResidualIsThePixelErrorInSigmas) {
  // Observation rotated by 2 px at f = 460 px (angle 2/460 rad); pixel sigma 0.5 px -> |r| ~= 4 sigmas.
  std::mt19937 rng(14);
  Scene s(rng, 10.0);
  const Eigen::Vector3d axis = s.f_Cj.cross(Eigen::Vector3d::UnitX()).normalized();
  const Eigen::Vector3d observed = Eigen::AngleAxisd(2.0 / 460.0, axis) * s.f_Cj;
  est::ReprojectionNoise noise;
  noise.pixel_sigma = 0.5;
  const est::ReprojectionFactor factor(s.f_Ca, observed, s.T_BC, noise.sqrt_information());
  Eigen::Vector2d r;
  const double* p[3] = {s.pose_a, s.pose_j, &s.rho};
  ASSERT_TRUE(factor.Evaluate(p, r.data(), nullptr));
  EXPECT_NEAR(r.norm(), 4.0, 1e-4);
  EXPECT_NEAR(factor.angular_error(s.pose_a, s.pose_j, s.rho) * 460.0, 2.0, 1e-9);
}

TEST(ReprojectionFactor, AnchorObservationIsSatisfiedByConstruction) {
  // With the observer equal to the anchor the prediction is the anchor bearing for every pose and inverse depth:
  // zero residual and zero Jacobians, so the estimator adds no factor for it.
  std::mt19937 rng(15);
  Scene s(rng, 20.0);
  std::copy(s.pose_a, s.pose_a + 7, s.pose_j);
  const est::ReprojectionFactor factor(s.f_Ca, s.f_Ca, s.T_BC, 460.0);
  for (double rho : {1e-6, 0.1, 2.0}) {
    double inverse_depth = rho;
    Eigen::VectorXd r;
    const auto J = ts::analytic_jacobians(factor, {s.pose_a, s.pose_j, &inverse_depth}, &r);
    EXPECT_LT(r.norm(), 1e-12);
    EXPECT_LT((J[0] + J[1]).norm(), 1e-9);  // moving both copies together changes nothing
    EXPECT_LT(J[2].norm(), 1e-9);
  }
}

TEST(ReprojectionFactor, PointAtInfinityIsFiniteAndCheiralityIsReported) {
  std::mt19937 rng(16);
  Scene s(rng, 10.0);
  const est::ReprojectionFactor factor(s.f_Ca, s.f_Cj, s.T_BC, 460.0);
  double rho = 0.0;
  Eigen::VectorXd r;
  const auto J = ts::analytic_jacobians(factor, {s.pose_a, s.pose_j, &rho}, &r);
  EXPECT_TRUE(r.allFinite());
  EXPECT_TRUE(J[2].allFinite());
  // The same geometry with the observation reversed: the point is behind that camera.
  const est::ReprojectionFactor behind(s.f_Ca, -s.f_Cj, s.T_BC, 460.0);
  EXPECT_FALSE(behind.in_front(s.pose_a, s.pose_j, s.rho));
  EXPECT_NEAR(behind.angular_error(s.pose_a, s.pose_j, s.rho), kPi, 1e-9);
}

TEST(ReprojectionNoise, RejectsNonPositiveValues) {
  est::ReprojectionNoise noise;
  noise.pixel_sigma = 0.0;
  EXPECT_THROW(noise.validate(), twinslam::InputError);
  noise = {};
  noise.focal_px = std::nan("");
  EXPECT_THROW(noise.validate(), twinslam::InputError);
}

TEST(ReprojectionFactor, JacobiansAreConsistentWithTheCeresPoseManifold) {
  // What the solver uses is J * PlusJacobian: it must equal the derivative of r(Plus(x, delta)) at delta = 0.
  std::mt19937 rng(17);
  Scene s(rng, 25.0);
  const est::ReprojectionFactor factor(s.f_Ca, (s.f_Cj + ts::random_vector(rng, 0.01)).normalized(), s.T_BC, 460.0);
  std::unique_ptr<ceres::Manifold> manifold(est::new_pose_manifold());
  const auto J = ts::analytic_jacobians(factor, s.params());
  double* poses[2] = {s.pose_a, s.pose_j};
  for (int b = 0; b < 2; ++b) {
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
    ASSERT_TRUE(manifold->PlusJacobian(poses[b], plus_jacobian.data()));
    const Eigen::MatrixXd analytic = J[b] * plus_jacobian;
    Eigen::MatrixXd numeric(2, 6);
    const double h = 1e-6;
    double original[7];
    std::copy(poses[b], poses[b] + 7, original);
    for (int k = 0; k < 6; ++k) {
      Eigen::Vector2d r[2];
      for (int side = 0; side < 2; ++side) {
        double delta[6] = {0, 0, 0, 0, 0, 0};
        delta[k] = side == 0 ? h : -h;
        ASSERT_TRUE(manifold->Plus(original, delta, poses[b]));
        const double* p[3] = {s.pose_a, s.pose_j, &s.rho};
        ASSERT_TRUE(factor.Evaluate(p, r[side].data(), nullptr));
      }
      std::copy(original, original + 7, poses[b]);
      numeric.col(k) = (r[0] - r[1]) / (2 * h);
    }
    EXPECT_LT(ts::max_relative_error(analytic, numeric), 1e-6) << "pose " << b;
  }
}

TEST(InverseDepthLandmark, PointAndInverseDepthRoundTripAndReanchoring) {
  std::mt19937 rng(18);
  const Eigen::Isometry3d T_BC = ts::forward_camera_T_BC();
  const Eigen::Isometry3d T_LB_a = ts::random_pose(rng), T_LB_n = ts::random_pose(rng);
  est::InverseDepthLandmark lm;
  lm.anchor_keyframe = 3;
  lm.f_Ca = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  lm.rho = 0.125;  // 8 m
  const Eigen::Vector3d p_L = est::point_in_local(T_LB_a, T_BC, lm.f_Ca, lm.rho);
  EXPECT_NEAR(((T_LB_a * T_BC).inverse() * p_L - 8.0 * lm.f_Ca).norm(), 0.0, 1e-12);
  ASSERT_TRUE(est::inverse_depth_along(T_LB_a, T_BC, lm.f_Ca, p_L).has_value());
  EXPECT_NEAR(*est::inverse_depth_along(T_LB_a, T_BC, lm.f_Ca, p_L), 0.125, 1e-14);
  EXPECT_FALSE(est::inverse_depth_along(T_LB_a, T_BC, -lm.f_Ca, p_L).has_value());  // behind

  // Pose block layout of imu_state.hpp.
  double block[7];
  ts::pack_pose(T_LB_a, block);
  EXPECT_LT((est::pose_from_block(block).matrix() - T_LB_a.matrix()).cwiseAbs().maxCoeff(), 1e-12);

  // Re-anchoring on the new anchor's exact observation keeps the point (any bearing on the sphere, also z < 0).
  const Eigen::Vector3d p_Cn = (T_LB_n * T_BC).inverse() * p_L;
  const auto moved = est::reanchor(lm, T_LB_a, T_LB_n, T_BC, 7, p_Cn.normalized());
  ASSERT_TRUE(moved.has_value());
  EXPECT_EQ(moved->anchor_keyframe, 7);
  EXPECT_LT((est::point_in_local(T_LB_n, T_BC, moved->f_Ca, moved->rho) - p_L).norm(), 1e-12);
  EXPECT_FALSE(est::reanchor(lm, T_LB_a, T_LB_n, T_BC, 7, -p_Cn.normalized()).has_value());
}
