// Visual-inertial bundle adjustment with the window's factors: recovery of perturbed keyframes from ideal data, and
// marginalization of the oldest keyframe at the optimum keeping the optimum of the rest (pose manifolds included).
#include <cmath>
#include <random>
#include <vector>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "ba_problem.hpp"
#include "twinslam/estimator/marginalization.hpp"
#include "twinslam/geometry/so3.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

constexpr double kRadToDeg = 57.29577951308232;

double position_error(const std::array<double, 7>& a, const std::array<double, 7>& b) {
  return (Eigen::Map<const Eigen::Vector3d>(a.data()) - Eigen::Map<const Eigen::Vector3d>(b.data())).norm();
}
double rotation_error(const std::array<double, 7>& a, const std::array<double, 7>& b) {
  const Eigen::Quaterniond qa(Eigen::Map<const Eigen::Quaterniond>(a.data() + 3));
  const Eigen::Quaterniond qb(Eigen::Map<const Eigen::Quaterniond>(b.data() + 3));
  return qa.normalized().angularDistance(qb.normalized());  // [rad]
}

ceres::Solver::Options tight_options() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.num_threads = 1;
  return options;
}

}  // namespace

TEST(BundleAdjustment, RecoversPerturbedKeyframesFromIdealData) {
  const ts::BaProblem p = ts::make_ba_problem(5, 50, 51);
  const ts::BaState truth = ts::true_ba_state(p);
  std::mt19937 rng(52);
  ts::BaState s = ts::perturbed_ba_state(p, rng);
  double worst_start = 0.0;
  for (std::size_t k = 1; k < 5; ++k) worst_start = std::max(worst_start, position_error(s.pose[k], truth.pose[k]));
  ASSERT_GT(worst_start, 0.05);  // the start is really off

  ceres::Problem problem;
  ts::add_ba_to_problem(p, s, problem);
  ceres::Solver::Options options = tight_options();
  options.max_num_iterations = 50;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();

  double worst_p = 0.0, worst_R = 0.0, worst_rho = 0.0;
  for (std::size_t k = 0; k < 5; ++k) {
    worst_p = std::max(worst_p, position_error(s.pose[k], truth.pose[k]));
    worst_R = std::max(worst_R, rotation_error(s.pose[k], truth.pose[k]));
  }
  for (std::size_t i = 0; i < s.rho.size(); ++i) worst_rho = std::max(worst_rho, std::abs(s.rho[i] / truth.rho[i] - 1));
  EXPECT_LT(worst_p, 0.01);                 // [m]
  EXPECT_LT(worst_R * kRadToDeg, 0.1);      // [deg]
  EXPECT_LT(worst_rho, 1e-3);               // relative
  for (std::size_t k = 0; k < 5; ++k) {
    const Eigen::Map<const Eigen::Vector3d> bg(s.speed_bias[k].data() + 3), ba(s.speed_bias[k].data() + 6);
    EXPECT_LT((bg - p.bias.gyro).norm(), 1e-3) << k;   // [rad/s]
    EXPECT_LT((ba - p.bias.accel).norm(), 5e-2) << k;  // [m/s^2]
  }
  RecordProperty("worst_position_error_m", std::to_string(worst_p));
  RecordProperty("worst_rotation_error_deg", std::to_string(worst_R * kRadToDeg));
  RecordProperty("iterations", std::to_string(summary.iterations.size()));
}

TEST(BundleAdjustment, MarginalizingTheOldestKeyframeAtTheOptimumKeepsTheOptimum) {
  // With noisy bearings (1 px) the optimum has non-zero residuals. Marginalizing keyframe 0 (pose, speed/bias and the
  // landmarks anchored there) at the optimum leaves the optimum of the remaining variables a stationary point of the
  // reduced problem (the prior carries exactly the gradient the removed factors contributed), so re-solving from a
  // perturbed start must land on the same values.
  ts::BaProblem p = ts::make_ba_problem(5, 50, 53);
  std::mt19937 rng(54);
  for (auto& lm : p.landmarks) {
    for (auto& o : lm.observations) o.f_C = (tg::so3_exp(ts::random_vector(rng, 1.0 / 460.0)) * o.f_C).normalized();
  }
  ts::BaState s = ts::perturbed_ba_state(p, rng);
  ceres::Problem problem;
  ts::add_ba_to_problem(p, s, problem, {}, /*fix_first_pose=*/false);
  // Gauge: a stiff prior on keyframe 0's pose (1 mm, 0.06 deg), built as a MarginalizationPrior with J0 = 1e3 I.
  auto* gauge = new est::MarginalizationPrior({s.pose[0].data()}, {est::BlockKind::kPose}, {7},
                                              1e3 * Eigen::MatrixXd::Identity(6, 6), Eigen::VectorXd::Zero(6));
  problem.AddResidualBlock(gauge, nullptr, s.pose[0].data());
  ceres::Solver::Summary summary;
  ceres::Solve(tight_options(), &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  const ts::BaState optimum = s;

  // Every factor touching the blocks to marginalize, as the sliding window will collect them.
  std::vector<double*> marginalized{s.pose[0].data(), s.speed_bias[0].data()};
  for (std::size_t i = 0; i < p.landmarks.size(); ++i) {
    if (p.landmarks[i].anchor == 0) marginalized.push_back(&s.rho[i]);
  }
  est::Marginalizer marginalizer;
  const auto connected = marginalizer.add_connected(problem, marginalized);
  EXPECT_GT(connected.size(), 2u);  // the IMU factor 0-1, the gauge prior and reprojection factors
  auto prior = marginalizer.marginalize();
  const std::vector<double*> prior_blocks = prior->parameter_blocks();
  // The prior need not have full rank on its blocks: the removed factors alone do not constrain every direction of
  // the kept blocks (the remaining factors do); truncated directions carry no information rather than noise.
  EXPECT_GT(prior->num_residuals(), 0);
  EXPECT_LE(prior->num_residuals(), prior->tangent_size());

  for (const auto id : connected) problem.RemoveResidualBlock(id);
  for (double* b : marginalized) problem.RemoveParameterBlock(b);
  problem.AddResidualBlock(prior.release(), nullptr, prior_blocks);

  // Start 1 cm / 0.3 deg away from the optimum and solve the reduced problem.
  for (std::size_t k = 1; k < 5; ++k) {
    double* pose = s.pose[k].data();
    Eigen::Map<Eigen::Vector3d>{pose} += ts::random_vector(rng, 0.01);
    Eigen::Map<Eigen::Vector4d>{pose + 3} =
        (Eigen::Map<Eigen::Quaterniond>(pose + 3) * tg::quaternion_exp(ts::random_vector(rng, 0.005))).coeffs();
  }
  ceres::Solve(tight_options(), &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  for (std::size_t k = 1; k < 5; ++k) {
    EXPECT_LT(position_error(s.pose[k], optimum.pose[k]), 1e-6) << k;  // [m]
    EXPECT_LT(rotation_error(s.pose[k], optimum.pose[k]), 1e-6) << k;  // [rad]
    for (int c = 0; c < 9; ++c) EXPECT_NEAR(s.speed_bias[k][c], optimum.speed_bias[k][c], 1e-6) << k << " " << c;
  }
  for (std::size_t i = 0; i < p.landmarks.size(); ++i) {
    if (p.landmarks[i].anchor != 0) {
      EXPECT_NEAR(s.rho[i], optimum.rho[i], 1e-6 * optimum.rho[i]) << i;
    }
  }
}
