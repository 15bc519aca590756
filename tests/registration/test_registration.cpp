// register_cloud end to end on the synthetic city: the known offset is recovered through noise and outliers, the
// information is a proper one, and every rejection reason can happen.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

#include "synthetic_twin.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/geometry/information_order.hpp"
#include "twinslam/geometry/so3.hpp"
#include "twinslam/registration/registration.hpp"

namespace twinslam::registration {
namespace {

const Eigen::Vector3d kBody = test::kCentre + Eigen::Vector3d(0.0, -5.0, 15.0);

struct Scene {
  TwinTileIndex index = test::make_index(test::sample_grid(test::city_surfaces(), 0.5));
  Eigen::Isometry3d error = test::offset_about(kBody, {0.3, -0.2, 1.0}, 3.0, {0.6, -0.7, 0.4});  // |t| ~ 1.0 m
  std::vector<Eigen::Vector3d> landmarks(int inliers, double outlier_fraction, unsigned seed = 11) const {
    auto p = test::sample_noisy(test::city_surfaces(), inliers, 0.1, seed);
    const auto o =
        test::sample_outliers(static_cast<int>(inliers * outlier_fraction / (1.0 - outlier_fraction)), seed + 1);
    p.insert(p.end(), o.begin(), o.end());
    return p;
  }
};

const Scene& scene() {
  static const Scene s;
  return s;
}

RegistrationConfig fine() {
  RegistrationConfig c;
  c.voxel_size_m = 0.0;  // keep every landmark: the accuracy test wants them all
  return c;
}

TEST(Registration, RecoversAKnownOffsetThroughNoiseAndOutliers) {
  const Scene& s = scene();
  EXPECT_NEAR((s.error * kBody - kBody).norm(), 1.0, 0.05);  // the body is off by 1 m and 3 deg
  const SourceInput in = test::make_source(s.landmarks(4000, 0.2), s.error, kBody);
  const RegistrationResult r = register_cloud(fine(), s.index, in);
  ASSERT_TRUE(r.accepted()) << r.reason;
  const Eigen::Isometry3d residual = r.correction_W * s.error;  // identity when the correction undoes the error
  // Translation error measured at the keyframe (the residual's own translation is about W's origin, 1.4 km away,
  // where 0.004 deg alone would be 0.1 m).
  EXPECT_LT(geometry::so3_log(residual.linear()).norm() * 180.0 / M_PI, 0.05);
  // The same check where the estimator will use it: the corrected keyframe position is the true one.
  const Eigen::Vector3d p_WB_true = kBody, p_WB_guess = s.error * kBody;
  EXPECT_LT((r.correction_W * p_WB_guess - p_WB_true).norm(), 0.01);
  EXPECT_LT((p_WB_guess + r.correction_xi.tail<3>() - p_WB_true).norm(), 0.01);  // xi's translation = dp at the body
  EXPECT_NEAR(r.rmse_m, 0.1, 0.03);
  EXPECT_GT(r.fitness, 0.6);
  EXPECT_GT(r.iterations, 1);
}

// The VIO cloud carries the window's scale error: landmarks at s x their true distance from the keyframe. Rigid ICP
// turns that into a position error of the keyframe; with estimate_scale the 7-DoF fit finds s, the keyframe's
// correction is right.
TEST(Registration, EstimatingTheScaleRemovesTheKeyframeBiasOfAScaledCloud) {
  const Scene& s = scene();
  const double scale = 1.03;
  std::vector<Eigen::Vector3d> scaled = s.landmarks(4000, 0.0);
  for (auto& p : scaled) p = kBody + scale * (p - kBody);
  const SourceInput in = test::make_source(scaled, s.error, kBody);
  const Eigen::Vector3d p_WB_guess = s.error * kBody;
  RegistrationConfig rigid = fine();
  rigid.estimate_scale = false;
  const RegistrationResult r_rigid = register_cloud(rigid, s.index, in);
  RegistrationConfig with_scale = fine();
  with_scale.estimate_scale = true;
  const RegistrationResult r_scale = register_cloud(with_scale, s.index, in);
  ASSERT_TRUE(r_scale.accepted()) << r_scale.reason;
  const double rigid_error_m = (r_rigid.correction_W * p_WB_guess - kBody).norm();
  const double scale_error_m = (r_scale.correction_W * p_WB_guess - kBody).norm();
  EXPECT_GT(rigid_error_m, 0.15);  // 3 % of the 15 m to the ground
  EXPECT_LT(scale_error_m, 0.02);
}

TEST(Registration, IsDeterministic) {
  const Scene& s = scene();
  const SourceInput in = test::make_source(s.landmarks(800, 0.2), s.error, kBody);
  const RegistrationResult a = register_cloud(RegistrationConfig{}, s.index, in);
  const RegistrationResult b = register_cloud(RegistrationConfig{}, s.index, in);
  EXPECT_EQ(a.correction_W.matrix(), b.correction_W.matrix());
  EXPECT_EQ(a.information, b.information);
}

// The parallel nearest-neighbour searches (threads > 1) change the time, never the answer: same points kept, same
// correspondences in the same order, bit-identical correction and information.
TEST(Registration, GivesTheSameResultOnAnyNumberOfThreads) {
  const Scene& s = scene();
  const SourceInput in = test::make_source(s.landmarks(2000, 0.2), s.error, kBody);
  RegistrationConfig one, four;
  four.threads = 4;
  const RegistrationResult a = register_cloud(one, s.index, in), b = register_cloud(four, s.index, in);
  ASSERT_TRUE(a.accepted()) << a.reason;
  EXPECT_EQ(a.source_points, b.source_points);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.correction_W.matrix(), b.correction_W.matrix());
  EXPECT_EQ(a.information, b.information);
  std::vector<Eigen::Vector3d> p;
  for (const Landmark& l : in.landmarks) p.push_back(l.p_L);
  EXPECT_EQ(statistical_inliers(p, kBody, 8, 2.0, 1), statistical_inliers(p, kBody, 8, 2.0, 3));
}

TEST(Registration, InformationIsSymmetricPositiveSemiDefiniteInEveryMode) {
  const Scene& s = scene();
  const SourceInput in = test::make_source(s.landmarks(1000, 0.2), s.error, kBody);
  for (WeightMode mode : {WeightMode::kPaper, WeightMode::kAdaptive, WeightMode::kFixed}) {
    RegistrationConfig c;
    c.weights = mode;
    const RegistrationResult r = register_cloud(c, s.index, in);
    ASSERT_TRUE(r.accepted()) << weight_mode_name(mode) << ": " << r.reason;
    for (const Matrix6d& M : {r.details.H, r.information}) {
      EXPECT_EQ((M - M.transpose()).norm(), 0.0);
      const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(M);
      EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().maxCoeff());
      EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);  // the city observes all six directions
    }
    EXPECT_EQ(r.details.zero_directions, 0);
  }
  RegistrationConfig paper;
  paper.weights = WeightMode::kPaper;
  paper.paper_beta = 3.0;
  const RegistrationResult p = register_cloud(paper, s.index, in);
  const double expected_scale = 3.0 / p.details.H.trace() * std::exp(-0.5 * p.rmse_m * p.rmse_m);
  EXPECT_NEAR((p.information - expected_scale * p.details.H).norm(), 0.0, 1e-12 * p.information.norm());  // eq. 10
}

RegistrationStatus status_of(const RegistrationConfig& c, const SourceInput& in,
                             const std::optional<Matrix6d>& prior = std::nullopt, std::string* reason = nullptr) {
  const RegistrationResult r = register_cloud(c, scene().index, in, prior);
  if (reason) *reason = r.reason;
  if (!r.accepted()) {
    EXPECT_FALSE(r.reason.empty());
    EXPECT_EQ(r.reason.find('\n'), std::string::npos);
    EXPECT_EQ(r.information, Matrix6d::Zero());
  }
  return r.status;
}

TEST(Registration, EveryRejectionReasonIsReachable) {
  const Scene& s = scene();
  const SourceInput in = test::make_source(s.landmarks(1000, 0.2), s.error, kBody);
  RegistrationConfig c;
  EXPECT_EQ(status_of(c, in), RegistrationStatus::kAccepted);
  std::string why;
  EXPECT_EQ(status_of(c, test::make_source(s.landmarks(20, 0.0), s.error, kBody), {}, &why),
            RegistrationStatus::kTooFewPoints);
  EXPECT_NE(why.find(" source points after preprocessing < min_points 30"), std::string::npos) << why;
  SourceInput far = in;  // the guess puts the cloud 1 km away from any loaded tile
  far.T_WL.translation() += Eigen::Vector3d(1000, 0, 0);
  EXPECT_EQ(status_of(c, far), RegistrationStatus::kTooFewInliers);
  RegistrationConfig one = c;
  one.max_iterations = 1;
  EXPECT_EQ(status_of(one, in, {}, &why), RegistrationStatus::kNotConverged);
  EXPECT_EQ(why, "ICP did not converge in 1 iterations (limit 1)");
  RegistrationConfig fit = c;
  fit.min_fitness = 0.95;  // 20 % outliers
  EXPECT_EQ(status_of(fit, in), RegistrationStatus::kFitnessTooLow);
  RegistrationConfig rmse = c;
  rmse.max_rmse_m = 0.02;  // 0.1 m noise
  EXPECT_EQ(status_of(rmse, in), RegistrationStatus::kRmseTooLarge);
  std::vector<test::Rect> ground{test::city_surfaces().front()};  // one plane: 3 unobservable directions
  RegistrationConfig rigid = c;
  rigid.estimate_scale = false;
  const SourceInput plane_only =
      test::make_source(test::sample_noisy(ground, 800, 0.05, 4), Eigen::Isometry3d::Identity(), kBody);
  EXPECT_EQ(status_of(rigid, plane_only, {}, &why), RegistrationStatus::kDegenerate);
  EXPECT_EQ(why, "3 poorly observed directions > max_zero_directions 2");
  // With the scale estimated too, the shift along the normal joins them (a scale about the keyframe moves the plane
  // the same way): ICP does not settle, and the cloud is refused all the same.
  EXPECT_NE(status_of(c, plane_only, {}, &why), RegistrationStatus::kAccepted);
  // The estimator says its pose is good to 1 cm / 0.01 rad: a 1 m correction contradicts it.
  Matrix6d tight = Matrix6d::Identity() * 1e-4;
  EXPECT_EQ(status_of(c, in, tight), RegistrationStatus::kCorrectionTooLarge);
  Matrix6d loose = Matrix6d::Identity();  // 1 rad, 1 m: the correction is plausible
  EXPECT_EQ(status_of(c, in, loose), RegistrationStatus::kAccepted);
  // The registration's own predicted position sigma: the accepted one states some; asked for ten times less, it is
  // refused and the reason says by how much.
  const RegistrationResult accepted = register_cloud(c, s.index, in);
  const double sigma_m = geometry::observed_position_sigma_m(accepted.information);
  ASSERT_GT(sigma_m, 0.0);
  RegistrationConfig sure = c;
  sure.max_position_sigma_m = 0.1 * sigma_m;
  EXPECT_EQ(status_of(sure, in, {}, &why), RegistrationStatus::kDegenerate);
  EXPECT_EQ(why.rfind("predicted position sigma ", 0), 0u) << why;
  sure.max_position_sigma_m = 10.0 * sigma_m;
  EXPECT_EQ(status_of(sure, in), RegistrationStatus::kAccepted);
}

TEST(Registration, CorridorIsAcceptedWithNoInformationAlongIt) {
  // A street canyon (two facades 10 m apart and the road, 120 m long in n): the position along the street is
  // unobservable. The registration is still useful (cross-street, height, attitude) and the estimator must get exactly
  // no information along the street, whatever ICP left there.
  const Eigen::Vector3d o = test::kCentre + Eigen::Vector3d(-5, -60, 0);
  const std::vector<test::Rect> street{{o, {10, 0, 0}, {0, 120, 0}},
                                       {o, {0, 120, 0}, {0, 0, 15}},
                                       {o + Eigen::Vector3d(10, 0, 0), {0, 120, 0}, {0, 0, 15}}};
  const TwinTileIndex index = test::make_index(test::sample_grid(street, 0.5));
  const Eigen::Vector3d body = test::kCentre + Eigen::Vector3d(0, 0, 5);
  const Eigen::Isometry3d error = test::offset_about(body, {0, 0, 1}, 1.0, {0.3, 0.5, 0.2});
  const RegistrationResult r = register_cloud(
      RegistrationConfig{}, index, test::make_source(test::sample_noisy(street, 1500, 0.05, 3), error, body));
  ASSERT_TRUE(r.accepted()) << r.reason;
  EXPECT_EQ(r.details.zero_directions, 1);
  Vector6d along;
  along << 0, 0, 0, 0, 1, 0;
  EXPECT_LT((r.information * along).norm(), 1e-9 * r.information.norm());
  const Eigen::Vector3d err = r.correction_W * (error * body) - body;
  EXPECT_LT(std::abs(err.x()), 0.02);  // across the street and height: recovered
  EXPECT_LT(std::abs(err.z()), 0.02);
  const Eigen::Matrix3d dR = (r.correction_W * error).linear();
  EXPECT_LT(geometry::so3_log(dR).norm() * 180.0 / M_PI, 0.05);
}

// An estimate 6 m off in height (a provisional GNSS alignment: urban GNSS is worst vertically): the ground and the
// roofs are beyond the fixed 3 m first gate, the facades say nothing about height, so ICP cannot find it. When the
// estimator's covariance says it is that unsure (3 m sigmas), the first gate covers 3 of them and the height is found.
TEST(Registration, TheFirstGateCoversThePositionUncertaintyTheEstimatorSends) {
  const Scene& s = scene();
  const Eigen::Isometry3d error = test::offset_about(kBody, {0, 0, 1}, 0.0, {0.0, 0.0, 6.0});
  const SourceInput in = test::make_source(s.landmarks(4000, 0.0), error, kBody);
  const auto height_error = [&](const RegistrationResult& r) { return (r.correction_W * (error * kBody) - kBody).norm(); };
  Matrix6d unsure = Matrix6d::Zero();
  unsure.diagonal() << Eigen::Vector3d::Constant(std::pow(0.5 * M_PI / 180.0, 2)), Eigen::Vector3d::Constant(9.0);
  const RegistrationResult found = register_cloud(fine(), s.index, in, unsure);
  ASSERT_TRUE(found.accepted()) << found.reason;
  EXPECT_LT(height_error(found), 0.05);
  RegistrationConfig fixed_gate = fine();
  fixed_gate.initial_threshold_sigmas = 0.0;
  const RegistrationResult stuck = register_cloud(fixed_gate, s.index, in, unsure);
  EXPECT_FALSE(stuck.accepted() && height_error(stuck) < 0.5) << height_error(stuck);
}

TEST(Registration, BadInputIsAnInputErrorNotACrash) {
  const Scene& s = scene();
  SourceInput in = test::make_source(s.landmarks(100, 0.0), s.error, kBody);
  Matrix6d not_pd = Matrix6d::Identity();
  not_pd(0, 0) = -1.0;
  EXPECT_THROW(register_cloud(RegistrationConfig{}, s.index, in, not_pd), InputError);
  in.landmarks[3].quality = 2.0;
  EXPECT_THROW(register_cloud(RegistrationConfig{}, s.index, in), InputError);
  in.landmarks[3].quality = 1.0;
  in.landmarks[4].cov_L(1, 2) = 0.5;  // not symmetric
  EXPECT_THROW(register_cloud(RegistrationConfig{}, s.index, in), InputError);
  in.landmarks[4].cov_L(1, 2) = 0.0;
  in.landmarks[5].p_L.x() = NAN;
  EXPECT_THROW(register_cloud(RegistrationConfig{}, s.index, in), InputError);
}

TEST(Registration, WeighsEachLandmarkByItsCovarianceAlongTheNormal) {
  // A third of the landmarks are far ones whose depth is poor: each is 0.3 m off along its viewing ray (here +x, as a
  // forward camera would see them; within the gate, so the robust kernel keeps them), and its covariance says so
  // (0.5 m along x). Weighted by it the registration ignores their error; every landmark counted the same
  // (surface_sigma_m 0, the paper's way) it is pulled along x.
  const Scene& s = scene();
  SourceInput in = test::make_source(s.landmarks(3000, 0.0), s.error, kBody);
  const Eigen::Matrix3d good = 0.05 * 0.05 * Eigen::Matrix3d::Identity();
  Eigen::Matrix3d deep = good;
  deep(0, 0) = 0.25;
  for (std::size_t i = 0; i < in.landmarks.size(); ++i) {
    in.landmarks[i].cov_L = i % 3 == 0 ? deep : good;
    if (i % 3 == 0) in.landmarks[i].p_L.x() += 0.3;
  }
  const Eigen::Vector3d p_WB_guess = s.error * kBody;
  const auto error_m = [&](const RegistrationConfig& c) {
    const RegistrationResult r = register_cloud(c, s.index, in);
    EXPECT_TRUE(r.accepted()) << r.reason;
    return (p_WB_guess + r.correction_xi.tail<3>() - kBody).norm();
  };
  RegistrationConfig weighted = fine();
  weighted.surface_sigma_m = 0.2;
  const double weighted_m = error_m(weighted), unweighted_m = error_m(fine());
  EXPECT_LT(weighted_m, 0.03) << "unweighted " << unweighted_m;
  EXPECT_GT(unweighted_m, 2.0 * weighted_m);
}

TEST(RegistrationPreprocess, DropsLowQualityDownsamplesAndRemovesOutliers) {
  SourceInput in;
  for (int i = 0; i < 200; ++i) in.landmarks.push_back({{0.01 * i, 0.0, 0.0}, i % 2 ? 0.9 : 0.1});  // 2 m line
  in.landmarks.push_back({{1.0, 30.0, 0.0}, 1.0});  // a lone point far from the rest
  in.T_WL.translation() = Eigen::Vector3d(1000, 2000, 30);
  RegistrationConfig c;
  c.voxel_size_m = 0.1;
  const SourceCloud out = preprocess(c, in);
  EXPECT_EQ(out.input, 201u);
  EXPECT_EQ(out.after_quality, 101u);
  EXPECT_EQ(out.after_voxel, 21u);                                 // 20 voxels of the line + the lone point
  EXPECT_EQ(out.p_W.size(), 20u);                                  // the lone point is a statistical outlier
  for (const auto& p : out.p_W) EXPECT_NEAR(p.y(), 2000.0, 1e-9);  // expressed in W with T_WL
  EXPECT_EQ(out.p_WB, Eigen::Vector3d(1000, 2000, 30));
}

}  // namespace
}  // namespace twinslam::registration
