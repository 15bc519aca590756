// ImuFactor: analytic Jacobians against numeric differentiation, zero residual at the truth, and a Ceres solve.
#include <memory>
#include <random>
#include <sstream>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "imu_test_utils.hpp"
#include "twinslam/estimator/imu_factor.hpp"
#include "twinslam/geometry/quaternion.hpp"
#include "twinslam/geometry/so3.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

namespace {

constexpr std::int64_t kTi = 1'003'000'000;
constexpr std::int64_t kTj = 1'512'000'000;

est::ImuBias true_bias() {
  est::ImuBias b;
  b.gyro << 0.004, -0.006, 0.002;
  b.accel << 0.08, -0.05, 0.12;
  return b;
}

std::shared_ptr<est::Preintegration> make_preintegration(const est::ImuBias& linearization_bias) {
  const ts::AnalyticTrajectory traj;
  const auto samples = ts::simulate_imu(traj, 0, 2'000'000'000, 200.0, true_bias());
  return std::make_shared<est::Preintegration>(est::PreintegrationConfig{}, linearization_bias, samples, kTi, kTj);
}

// A state near `s`: rotation perturbed by up to ~0.2 rad, the rest by amounts well beyond the noise.
est::ImuState perturb(est::ImuState s, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  auto v3 = [&](double sigma) { return Eigen::Vector3d(sigma * n(rng), sigma * n(rng), sigma * n(rng)); };
  s.p_L += v3(0.3);
  s.q_LB = s.q_LB * tg::quaternion_exp(v3(0.1));
  s.v_L += v3(0.2);
  s.bias.gyro += v3(0.005);
  s.bias.accel += v3(0.05);
  return s;
}

struct Blocks {
  double pose_i[7], sb_i[9], pose_j[7], sb_j[9];
  const double* params[4] = {pose_i, sb_i, pose_j, sb_j};
  Blocks(const est::ImuState& i, const est::ImuState& j) {
    est::pack(i, pose_i, sb_i);
    est::pack(j, pose_j, sb_j);
  }
};

// Reference Jacobians by Ridders' extrapolated central differences on the factor's own residual.
struct ResidualOnly {
  const est::ImuFactor* factor;
  bool operator()(const double* a, const double* b, const double* c, const double* d, double* r) const {
    const double* p[4] = {a, b, c, d};
    return factor->Evaluate(p, r, nullptr);
  }
};

double max_relative_error(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / numeric.cwiseAbs().maxCoeff();
}

}  // namespace

TEST(ImuFactor, AnalyticJacobiansMatchNumericAtRandomStates) {
  const ts::AnalyticTrajectory traj;
  std::mt19937 rng(7);
  const int sizes[4] = {7, 9, 7, 9};
  double worst = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    // Linearization bias away from the true one and states away from the truth: every term is exercised,
    // including the bias-correction rotation Jacobian and Jr^-1 of a non-zero rotation residual.
    est::ImuBias lin = true_bias();
    lin.gyro += Eigen::Vector3d(0.003, 0.002, -0.004);
    const est::ImuFactor factor(make_preintegration(lin));
    const Blocks x(perturb(ts::true_state(traj, kTi, true_bias()), rng),
                   perturb(ts::true_state(traj, kTj, true_bias()), rng));

    double residual[15];
    Eigen::Matrix<double, 15, 9, Eigen::RowMajor> analytic[4];
    double* jac[4] = {analytic[0].data(), analytic[1].data(), analytic[2].data(), analytic[3].data()};
    ASSERT_TRUE(factor.Evaluate(x.params, residual, jac));

    ceres::NumericDiffOptions options;
    const ceres::NumericDiffCostFunction<ResidualOnly, ceres::RIDDERS, 15, 7, 9, 7, 9> numeric(
        new ResidualOnly{&factor}, ceres::TAKE_OWNERSHIP, 15, options);
    double residual_n[15];
    Eigen::Matrix<double, 15, 9, Eigen::RowMajor> num[4];
    double* jac_n[4] = {num[0].data(), num[1].data(), num[2].data(), num[3].data()};
    ASSERT_TRUE(numeric.Evaluate(x.params, residual_n, jac_n));

    for (int b = 0; b < 4; ++b) {
      // Row-major 15 x sizes[b] blocks stored at the start of each buffer.
      const Eigen::Map<const Eigen::Matrix<double, 15, Eigen::Dynamic, Eigen::RowMajor>> A(jac[b], 15, sizes[b]);
      const Eigen::Map<const Eigen::Matrix<double, 15, Eigen::Dynamic, Eigen::RowMajor>> N(jac_n[b], 15, sizes[b]);
      const double err = max_relative_error(A, N);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-6) << "trial " << trial << " block " << b << "\nanalytic\n" << A << "\nnumeric\n" << N;
    }
  }
  std::ostringstream text;
  text << std::scientific << worst;
  RecordProperty("worst_relative_error", text.str());
}

TEST(ImuFactor, JacobiansAreConsistentWithTheCeresPoseManifold) {
  // What the solver uses is J * PlusJacobian: it must equal the derivative of r(Plus(x, delta)) at delta = 0.
  const ts::AnalyticTrajectory traj;
  std::mt19937 rng(8);
  const est::ImuFactor factor(make_preintegration(true_bias()));
  Blocks x(perturb(ts::true_state(traj, kTi, true_bias()), rng), perturb(ts::true_state(traj, kTj, true_bias()), rng));
  std::unique_ptr<ceres::Manifold> manifold(est::new_pose_manifold());

  double residual[15];
  Eigen::Matrix<double, 15, 7, Eigen::RowMajor> J[2];
  Eigen::Matrix<double, 15, 9, Eigen::RowMajor> unused[2];
  double* jac[4] = {J[0].data(), unused[0].data(), J[1].data(), unused[1].data()};
  ASSERT_TRUE(factor.Evaluate(x.params, residual, jac));

  double* poses[2] = {x.pose_i, x.pose_j};
  for (int b = 0; b < 2; ++b) {
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
    ASSERT_TRUE(manifold->PlusJacobian(poses[b], plus_jacobian.data()));
    const Eigen::Matrix<double, 15, 6> analytic = J[b] * plus_jacobian;
    Eigen::Matrix<double, 15, 6> numeric;
    const double h = 1e-6;
    for (int k = 0; k < 6; ++k) {
      double original[7], moved[7];
      std::copy(poses[b], poses[b] + 7, original);
      Eigen::Matrix<double, 15, 1> r[2];
      for (int side = 0; side < 2; ++side) {
        double delta[6] = {0, 0, 0, 0, 0, 0};
        delta[k] = side == 0 ? h : -h;
        ASSERT_TRUE(manifold->Plus(original, delta, moved));
        std::copy(moved, moved + 7, poses[b]);
        ASSERT_TRUE(factor.Evaluate(x.params, r[side].data(), nullptr));
      }
      std::copy(original, original + 7, poses[b]);
      numeric.col(k) = (r[0] - r[1]) / (2 * h);
    }
    EXPECT_LT(max_relative_error(analytic, numeric), 1e-6) << "pose " << b;
  }
}

TEST(ImuFactor, ResidualVanishesAtTheTrueStates) {
  const ts::AnalyticTrajectory traj;
  const auto pre = make_preintegration(true_bias());
  const est::ImuState si = ts::true_state(traj, kTi, true_bias());
  const est::ImuState sj = ts::true_state(traj, kTj, true_bias());
  const est::Vector15d r = est::imu_residual(*pre, si, sj, ts::kGravity_W);
  // What remains is the midpoint discretization error over 0.5 s (~1e-6), far below the 0.01 deg / 1 mm bounds.
  EXPECT_LT(r.segment<3>(0).norm(), 1e-5);  // rad
  EXPECT_LT(r.segment<3>(3).norm(), 1e-5);  // m/s
  EXPECT_LT(r.segment<3>(6).norm(), 1e-5);  // m
  EXPECT_EQ(r.tail<6>().norm(), 0.0);
  // Whitened, the residual is far below one standard deviation.
  const est::ImuFactor factor(pre);
  const Blocks x(si, sj);
  est::Vector15d whitened;
  ASSERT_TRUE(factor.Evaluate(x.params, whitened.data(), nullptr));
  EXPECT_LT(whitened.norm(), 1e-2);
  // A 1 cm position error at j, by contrast, is many standard deviations over half a second.
  est::ImuState off = sj;
  off.p_L.x() += 0.01;
  const Blocks y(si, off);
  ASSERT_TRUE(factor.Evaluate(y.params, whitened.data(), nullptr));
  EXPECT_GT(whitened.norm(), 3.0);
  // The factor whitens exactly with the square-root information: r^T Sigma^-1 r.
  const est::Vector15d r_off = est::imu_residual(*pre, si, off, ts::kGravity_W);
  const double mahalanobis2 = r_off.dot(pre->residual_covariance().inverse() * r_off);
  EXPECT_NEAR(whitened.squaredNorm(), mahalanobis2, 1e-9 * mahalanobis2);
}

TEST(ImuFactor, CeresRecoversStateJFromStateI) {
  // With state i fixed the factor alone determines all 15 degrees of freedom of state j: the solver must land on the
  // prediction (zero residual) from a start 0.2 rad and decimetres away, which exercises the Jacobians, the manifold
  // and the whitening together.
  const ts::AnalyticTrajectory traj;
  std::mt19937 rng(9);
  const auto pre = make_preintegration(true_bias());
  const est::ImuState si = ts::true_state(traj, kTi, true_bias());
  const est::ImuState truth_j = ts::true_state(traj, kTj, true_bias());
  Blocks x(si, perturb(truth_j, rng));

  ceres::Problem problem;
  problem.AddResidualBlock(new est::ImuFactor(pre), nullptr, x.pose_i, x.sb_i, x.pose_j, x.sb_j);
  problem.SetManifold(x.pose_i, est::new_pose_manifold());
  problem.SetManifold(x.pose_j, est::new_pose_manifold());
  problem.SetParameterBlockConstant(x.pose_i);
  problem.SetParameterBlockConstant(x.sb_i);
  ceres::Solver::Options options;
  options.max_num_iterations = 20;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();

  const est::ImuState sj = est::unpack(x.pose_j, x.sb_j);
  const est::ImuState optimum = est::predict(si, *pre, ts::kGravity_W);
  EXPECT_LT((sj.p_L - optimum.p_L).norm(), 1e-9);
  EXPECT_LT(sj.q_LB.angularDistance(optimum.q_LB), 1e-9);
  EXPECT_LT((sj.v_L - optimum.v_L).norm(), 1e-9);
  EXPECT_LT((sj.bias.gyro - truth_j.bias.gyro).norm(), 1e-12);
  EXPECT_LT((sj.bias.accel - truth_j.bias.accel).norm(), 1e-12);
  // and the optimum is the true state up to the integration error.
  EXPECT_LT((sj.p_L - truth_j.p_L).norm(), 1e-5);
  EXPECT_LT(sj.q_LB.angularDistance(truth_j.q_LB), 1e-5);
}
