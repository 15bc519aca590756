// RANSAC on bearings: injected outliers (tracks moved by 20 px across their epipolar line) are found, inliers kept,
// for both models, for a pinhole-like field of view and for fisheye rays beyond 90 degrees.
#include <gtest/gtest.h>

#include <random>

#include "twinslam/geometry/so3.hpp"
#include "twinslam/tracking/ransac.hpp"

namespace twinslam::tracking {
namespace {

constexpr double kFocalPx = 400.0;  // px per rad: converts the "px" of the test into angles

struct Matches {
  std::vector<Eigen::Vector3d> f_prev, f_curr;
  std::vector<bool> outlier;
  Eigen::Matrix3d R_prev_curr;
};

// Points around the camera at 2..20 m, seen from prev (identity) and curr (R_prev_curr, t_prev_curr) with 0.1 px of
// bearing noise. min_z: smallest z/|p| of the points in prev (negative = beyond 90 degrees from the optical axis).
// Every `outlier_every`-th match is moved by 20 px perpendicular to its epipolar plane (0 = no outliers).
Matches make_matches(int n, double min_z, const Eigen::Vector3d& t_prev_curr, int outlier_every, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> depth(2.0, 20.0);
  Matches m;
  m.R_prev_curr = geometry::so3_exp(Eigen::Vector3d(0.05, -0.02, 0.03));
  const Eigen::Matrix3d E_curr_prev = geometry::skew(-m.R_prev_curr.transpose() * t_prev_curr) *
                                      m.R_prev_curr.transpose();  // t_curr_prev = -R^T t_prev_curr
  while (static_cast<int>(m.f_prev.size()) < n) {
    Eigen::Vector3d dir(gauss(rng), gauss(rng), gauss(rng));
    dir.normalize();
    if (dir.z() < min_z) continue;
    const Eigen::Vector3d p_prev = depth(rng) * dir;
    const Eigen::Vector3d p_curr = m.R_prev_curr.transpose() * (p_prev - t_prev_curr);
    auto noisy = [&](const Eigen::Vector3d& f) {
      return (f + Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)) * (0.1 / kFocalPx)).normalized();
    };
    Eigen::Vector3d f_prev = noisy(p_prev.normalized());
    Eigen::Vector3d f_curr = noisy(p_curr.normalized());
    const bool outlier = outlier_every > 0 && m.f_prev.size() % outlier_every == 0;
    if (outlier) f_curr = (f_curr + (20.0 / kFocalPx) * (E_curr_prev * f_prev).normalized()).normalized();
    m.f_prev.push_back(f_prev);
    m.f_curr.push_back(f_curr);
    m.outlier.push_back(outlier);
  }
  return m;
}

RansacOptions options() {
  RansacOptions o;
  o.threshold_rad = 1.0 / kFocalPx;  // 1 px
  return o;
}

void expect_separates(const Matches& m, const RansacResult& r) {
  ASSERT_EQ(r.inlier.size(), m.f_prev.size());
  int outliers = 0, outliers_kept = 0, inliers = 0, inliers_dropped = 0;
  for (std::size_t i = 0; i < m.outlier.size(); ++i) {
    if (m.outlier[i]) {
      ++outliers;
      outliers_kept += r.inlier[i] ? 1 : 0;
    } else {
      ++inliers;
      inliers_dropped += r.inlier[i] ? 0 : 1;
    }
  }
  EXPECT_EQ(outliers_kept, 0) << "of " << outliers << " injected outliers";
  EXPECT_LE(inliers_dropped, inliers / 50) << "of " << inliers << " inliers";  // at most 2 %
}

TEST(Ransac, KnownRotationRemovesInjectedOutliersPinholeFov) {
  const Matches m = make_matches(150, 0.8, Eigen::Vector3d(0.3, 0.05, 0.1), 25, 1);
  expect_separates(m, ransac_known_rotation(m.f_prev, m.f_curr, m.R_prev_curr, options()));
}

TEST(Ransac, EssentialRemovesInjectedOutliersPinholeFov) {
  const Matches m = make_matches(150, 0.8, Eigen::Vector3d(0.3, 0.05, 0.1), 25, 2);
  expect_separates(m, ransac_essential(m.f_prev, m.f_curr, options()));
}

TEST(Ransac, BothModelsWorkForFisheyeRaysBeyond90Degrees) {
  const Matches m = make_matches(150, -0.4, Eigen::Vector3d(-0.1, 0.2, 0.25), 20, 3);  // up to 114 deg off-axis
  int beyond = 0;
  for (const auto& f : m.f_prev) beyond += f.z() < 0.0 ? 1 : 0;
  ASSERT_GT(beyond, 10);
  expect_separates(m, ransac_known_rotation(m.f_prev, m.f_curr, m.R_prev_curr, options()));
  expect_separates(m, ransac_essential(m.f_prev, m.f_curr, options()));
}

TEST(Ransac, PureRotationKeepsEveryMatch) {
  // No translation: the epipolar geometry is degenerate, but every correct match must still be accepted.
  const Matches m = make_matches(120, 0.8, Eigen::Vector3d::Zero(), 0, 4);
  EXPECT_EQ(ransac_known_rotation(m.f_prev, m.f_curr, m.R_prev_curr, options()).num_inliers, 120);
  EXPECT_EQ(ransac_essential(m.f_prev, m.f_curr, options()).num_inliers, 120);
}

TEST(Ransac, TooFewMatchesAreAllKept) {
  const Matches m = make_matches(7, 0.8, Eigen::Vector3d(0.3, 0, 0), 0, 5);
  EXPECT_EQ(ransac_essential(m.f_prev, m.f_curr, options()).num_inliers, 7);
  const std::vector<Eigen::Vector3d> one(1, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(ransac_known_rotation(one, one, Eigen::Matrix3d::Identity(), options()).num_inliers, 1);
}

TEST(Ransac, EpipolarAngleIsTheAngleToTheEpipolarPlane) {
  // Translation along x, no rotation: the epipolar plane of f_prev = z contains x and z; a bearing tilted by
  // 0.01 rad about x out of that plane has residual sin(0.01).
  const Eigen::Matrix3d E = geometry::skew(Eigen::Vector3d::UnitX());
  const Eigen::Vector3d f_curr(0.0, std::sin(0.01), std::cos(0.01));
  EXPECT_NEAR(epipolar_angle(E, Eigen::Vector3d::UnitZ(), f_curr), std::sin(0.01), 1e-12);
  EXPECT_NEAR(epipolar_angle(E, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0.6, 0.0, 0.8)), 0.0, 1e-15);
}

}  // namespace
}  // namespace twinslam::tracking
