// The heading search (yaw_search.hpp): which starts it tries, that it finds a heading plain ICP misses, and that it
// refuses a heading the geometry does not determine.
#include <gtest/gtest.h>

#include "synthetic_twin.hpp"
#include "twinslam/geometry/so3.hpp"
#include "twinslam/registration/registration.hpp"
#include "twinslam/registration/yaw_search.hpp"

namespace twinslam::registration {
namespace {

const Eigen::Vector3d kBody = test::kCentre + Eigen::Vector3d(0.0, -5.0, 15.0);

// The estimator's covariance (rotation, translation): heading sigma `yaw_deg`, 0.5 deg roll/pitch, 1 m position.
Matrix6d prior_with_heading_sigma(double yaw_deg) {
  Matrix6d S = Matrix6d::Zero();
  const double d = M_PI / 180.0;
  S.diagonal() << std::pow(0.5 * d, 2), std::pow(0.5 * d, 2), std::pow(yaw_deg * d, 2), 1.0, 1.0, 1.0;
  return S;
}

TEST(YawSearch, StartsOnlyWhenTheHeadingIsUncertainWithinThreeSigmaAndTheCap) {
  const RegistrationConfig c;  // min sigma 1 deg, step 2 deg, cap 45 deg
  EXPECT_EQ(yaw_starts_deg(c, std::nullopt), std::vector<double>{0.0});
  EXPECT_EQ(yaw_starts_deg(c, 0.9), std::vector<double>{0.0});
  EXPECT_EQ(yaw_starts_deg(c, 2.0), (std::vector<double>{0.0, -2.0, 2.0, -4.0, 4.0, -6.0, 6.0}));
  EXPECT_EQ(yaw_starts_deg(c, 10.0).size(), 31u);  // +-30 deg: 3 sigma
  EXPECT_EQ(yaw_starts_deg(c, 30.0).size(), 45u);  // +-44 deg: the cap (a provisional GNSS alignment)
  EXPECT_EQ(yaw_starts_deg(c, 30.0).back(), 44.0);
}

TEST(YawSearch, FindsAHeadingErrorPlainIcpDoesNotConvergeFrom) {
  // 9 deg of heading error about the body (a GNSS alignment from a short, noisy baseline) and 1 m of position:
  // facades 20-40 m away are displaced by 3-6 m, beyond ICP's 3 m first gate.
  const auto surfaces = test::city_surfaces();
  const TwinTileIndex index = test::make_index(test::sample_grid(surfaces, 0.5));
  const Eigen::Isometry3d error = test::offset_about(kBody, {0, 0, 1}, 9.0, {0.6, -0.5, 0.3});
  const SourceInput in = test::make_source(test::sample_noisy(surfaces, 1500, 0.1, 21), error, kBody);
  const auto heading_error_deg = [&](const RegistrationResult& r) {
    return geometry::so3_log((r.correction_W * error).linear()).norm() * 180.0 / M_PI;
  };
  RegistrationConfig c;
  c.max_mahalanobis_sq = 1e12;  // this test is about the heading, not the gate
  const RegistrationResult plain = register_cloud(c, index, in, prior_with_heading_sigma(0.5));
  EXPECT_EQ(plain.yaw_starts, 1);
  EXPECT_TRUE(!plain.accepted() || heading_error_deg(plain) > 1.0) << "plain ICP found it: the test shows nothing";
  const RegistrationResult searched = register_cloud(c, index, in, prior_with_heading_sigma(4.0));
  EXPECT_EQ(searched.yaw_starts, 13);  // +-12 deg: 3 sigma
  ASSERT_TRUE(searched.accepted()) << searched.reason;
  EXPECT_LT(heading_error_deg(searched), 0.05);
  EXPECT_LT((searched.correction_W * (error * kBody) - kBody).norm(), 0.02);
}

TEST(YawSearch, ARoundTowerLeavesTheHeadingOpenAndIsRejected) {
  // Ground and a round tower of radius 25 m centred under the body: every heading fits the same.
  std::vector<test::Rect> surfaces{test::city_surfaces().front()};
  const int facets = 72;
  for (int k = 0; k < facets; ++k) {
    const double a0 = 2.0 * M_PI * k / facets, a1 = 2.0 * M_PI * (k + 1) / facets;
    const Eigen::Vector3d p0 = kBody + 25.0 * Eigen::Vector3d(std::cos(a0), std::sin(a0), 0.0);
    const Eigen::Vector3d p1 = kBody + 25.0 * Eigen::Vector3d(std::cos(a1), std::sin(a1), 0.0);
    const Eigen::Vector3d base(p0.x(), p0.y(), 0.0);
    surfaces.push_back({base, p1 - p0, {0.0, 0.0, 40.0}});
  }
  const TwinTileIndex index = test::make_index(test::sample_grid(surfaces, 0.5));
  const Eigen::Isometry3d error = test::offset_about(kBody, {0, 0, 1}, 3.0, {0.3, -0.2, 0.1});
  const SourceInput in = test::make_source(test::sample_noisy(surfaces, 1500, 0.05, 22), error, kBody);
  RegistrationConfig c;
  c.max_zero_directions = 6;  // so that only the heading test can refuse it
  const RegistrationResult r = register_cloud(c, index, in, prior_with_heading_sigma(4.0));
  EXPECT_EQ(r.status, RegistrationStatus::kDegenerate);
  EXPECT_NE(r.reason.find("heading ambiguous"), std::string::npos) << r.reason;
}

}  // namespace
}  // namespace twinslam::registration
