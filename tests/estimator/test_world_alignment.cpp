// Issue 11 acceptance: a global (W-frame) factor added through the provider interface estimates the world alignment
// T_WL, its information survives marginalization, and the marginalization prior built from the one term list is the
// dense Schur complement of the Hessian built from the same list.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Cholesky>

#include "position_provider.hpp"
#include "sliding_window_sim.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/estimator/sliding_window_state.hpp"

namespace twinslam::estimator {
namespace {

using testing::PositionProvider;
using testing::SimRun;

constexpr double kDeg = 3.14159265358979 / 180.0;

// A 60 s figure-eight (50 x 25 m, about 2 m/s, turning all the while) through the middle of a landmark shell 30-45 m
// out, so the flight never comes close to a landmark. The yaw of T_WL is then known to 0.23 deg (1 sigma) from the
// 1 m fixes; with fewer or farther landmarks the VIO's own heading drift (which T_WL partly absorbs) reaches 0.4 deg.
SimRun sixty_second_flight() {
  testing::AnalyticTrajectory traj;
  const double w = 2.0 * M_PI / 60.0;
  traj.position[0] = {0.0, 0.0, 25.0, w, 0.0};        // x = 25 sin(w t) [m]
  traj.position[1] = {0.0, 0.0, 12.5, 2.0 * w, 0.0};  // y = 12.5 sin(2 w t) [m]
  return testing::make_sim_run(60.0, 0.5, 5, 8000, 460.0, traj, {30.0, 45.0, 45.0});
}

Eigen::Isometry3d true_T_WL() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(25.0 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() << 12.0, -7.0, 3.0;
  return T;
}

SlidingWindowConfig config_for(const SimRun& run) {
  SlidingWindowConfig c;
  c.T_BC = run.T_BC;
  c.pixel_sigma = 0.5;
  c.max_solver_time_s = 10.0;  // deterministic: only the iteration count bounds the solver
  return c;
}

struct Flight {
  std::vector<FrameEstimate> estimates;
  std::optional<Eigen::Matrix<double, 6, 6>> oldest_cov_W;  // oldest keyframe, T_WB tangent [dp_W, dtheta_B]
  std::optional<Eigen::Matrix4d> T_WL_cov;
};

// Feeds the run from its true initial state (L = the simulation's frame); with `provider`, every frame also gets a
// fix z_W = T_WL_true p_LB_true + 1 m noise per axis.
Flight fly(SlidingWindowEstimator& est, const SimRun& run, PositionProvider* provider, std::size_t frames = 0) {
  std::mt19937 rng(99);
  std::normal_distribution<double> noise(0.0, 1.0);
  Flight out;
  est.initialize_next_frame(run.frames.front().truth);
  std::size_t imu_next = 0;
  const std::size_t n = frames == 0 ? run.frames.size() : frames;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& f = run.frames[k];
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns + 5'000'000) {
      est.add_imu(run.imu[imu_next++]);
    }
    if (provider != nullptr) {
      const Eigen::Vector3d z_W = true_T_WL() * f.truth.p_L + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      provider->add_fix(f.stamp_ns, z_W, 1.0);
    }
    out.estimates.push_back(est.add_frame(f.stamp_ns, f.features));
  }
  out.oldest_cov_W = est.pose_covariance_world(est.window_stamps().front());
  out.T_WL_cov = est.world_alignment_covariance();
  return out;
}

double yaw_of(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

double yaw_error_deg(const Eigen::Isometry3d& T_WL) {
  return std::abs(std::remainder(yaw_of(T_WL) - yaw_of(true_T_WL()), 2 * M_PI)) / kDeg;
}

TEST(WorldAlignment, PositionFactorInWorldPullsTwlToTruthAndSurvivesMarginalization) {
  const SimRun run = sixty_second_flight();
  SlidingWindowEstimator with(config_for(run));
  auto provider = std::make_shared<PositionProvider>();
  with.add_factor_provider(provider);
  const Flight a = fly(with, run, provider.get());

  const FrameEstimate& last = a.estimates.back();
  ASSERT_EQ(last.status, EstimatorStatus::kTracking);
  ASSERT_TRUE(last.aligned);
  const double dp = (last.T_WL.translation() - true_T_WL().translation()).norm();
  std::printf("T_WL error after 60 s: %.3f m, %.3f deg (started at the identity: 14 m / 25 deg off)\n", dp,
              yaw_error_deg(last.T_WL));
  EXPECT_LT(dp, 0.2);
  EXPECT_LT(yaw_error_deg(last.T_WL), 0.5);
  // What a user sees: the vehicle in W.
  const Eigen::Matrix3d R_true = true_T_WL().linear() * run.frames.back().truth.q_LB.toRotationMatrix();
  const Eigen::Matrix3d R_est = last.T_WL.linear() * last.T_LB.linear();
  std::printf("last pose in W: %.3f m, heading %.3f deg off\n",
              ((last.T_WL * last.T_LB).translation() - true_T_WL() * run.frames.back().truth.p_L).norm(),
              Eigen::AngleAxisd(R_true.transpose() * R_est).angle() / kDeg);

  // Survives marginalization: the same fixes, but withheld from the oldest keyframe so none is ever marginalized (the
  // estimator before issue 11 dropped them there). Only the window's <= 8 fixes of 1 m then inform T_WL.
  SlidingWindowEstimator dropped(config_for(run));
  auto withheld = std::make_shared<PositionProvider>(/*withhold_oldest=*/true);
  dropped.add_factor_provider(withheld);
  const Flight b = fly(dropped, run, withheld.get());
  EXPECT_GT(provider->marginalized, 50u);
  ASSERT_TRUE(a.T_WL_cov && b.T_WL_cov && a.oldest_cov_W && b.oldest_cov_W);
  const auto sigma_p = [](const Eigen::Matrix4d& c) { return std::sqrt(c.topLeftCorner<3, 3>().trace() / 3.0); };
  const auto sigma_oldest = [](const Eigen::Matrix<double, 6, 6>& c) { return std::sqrt(c.topLeftCorner<3, 3>().trace()); };
  std::printf("T_WL sigma: %.3f m / %.3f deg (fixes marginalized) vs %.3f m / %.3f deg (dropped)\n", sigma_p(*a.T_WL_cov),
              std::sqrt((*a.T_WL_cov)(3, 3)) / kDeg, sigma_p(*b.T_WL_cov), std::sqrt((*b.T_WL_cov)(3, 3)) / kDeg);
  std::printf("oldest keyframe, position sigma in W: %.3f m (marginalized) vs %.3f m (dropped); T_WL error dropped: "
              "%.3f m, %.3f deg\n", sigma_oldest(*a.oldest_cov_W), sigma_oldest(*b.oldest_cov_W),
              (b.estimates.back().T_WL.translation() - true_T_WL().translation()).norm(),
              yaw_error_deg(b.estimates.back().T_WL));
  EXPECT_LT(sigma_p(*a.T_WL_cov), 0.5 * sigma_p(*b.T_WL_cov));
  EXPECT_LT(sigma_oldest(*a.oldest_cov_W), 0.5 * sigma_oldest(*b.oldest_cov_W));
}

TEST(WorldAlignment, VioOnlyNeverTouchesTheAlignment) {
  const SimRun run = sixty_second_flight();
  SlidingWindowEstimator est(config_for(run));
  const Flight f = fly(est, run, nullptr, 200);
  EXPECT_FALSE(f.estimates.back().aligned);
  EXPECT_TRUE(f.estimates.back().T_WL.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_FALSE(est.world_alignment_covariance().has_value());
  // Without T_WL the world covariance is the local one.
  const std::int64_t oldest = est.window_stamps().front();
  EXPECT_TRUE(est.pose_covariance_world(oldest)->isApprox(*est.pose_covariance(oldest)));
}

// Schur complement of the marginalized blocks in `H` (offsets of lin), on the kept blocks.
Eigen::MatrixXd schur(const DenseLinearization& lin) {
  const int m = lin.marginalized_tangent;
  const int n = static_cast<int>(lin.H.rows()) - m;
  const Eigen::MatrixXd Hmm = lin.H.topLeftCorner(m, m);
  const Eigen::MatrixXd Hrm = lin.H.bottomLeftCorner(n, m);
  return lin.H.bottomRightCorner(n, n) - Hrm * Hmm.ldlt().solve(Hrm.transpose());
}

TEST(WorldAlignment, PriorFromTheTermListIsTheDenseSchurComplementWithAProviderTerm) {
  const SimRun run = sixty_second_flight();
  SlidingWindowEstimator est(config_for(run));
  auto provider = std::make_shared<PositionProvider>();
  est.add_factor_provider(provider);
  // 10 s: the window is full and has slid many times; its oldest keyframe carries a fix.
  fly(est, run, provider.get(), 200);
  WindowState& s = est.internal_state();
  ASSERT_GE(static_cast<int>(s.frames.size()), s.config.window_keyframes);

  const std::vector<ResidualTerm> terms = build_window_terms(s);
  const MarginalizationSelection sel = select_for_marginalization(s, terms);
  const bool provider_term_on_k0 = std::any_of(sel.terms.begin(), sel.terms.end(), [&](const ResidualTerm& t) {
    return t.kind == TermKind::kProvider && touches(t, s.frames.front()->pose.data());
  });
  ASSERT_TRUE(provider_term_on_k0) << "the oldest keyframe must carry a fix for this test";

  // The dense Hessian of the WHOLE list, marginalized blocks first; minus the terms that do not act on them.
  Marginalizer all(s.config.marginalization), rest(s.config.marginalization);
  for (const auto& t : terms) all.add_factor(t.cost.get(), t.loss.get(), t.blocks);
  for (double* b : sel.blocks) all.marginalize_block(b);
  for (const auto& t : terms) {
    const bool selected = std::any_of(sel.terms.begin(), sel.terms.end(),
                                      [&](const ResidualTerm& u) { return u.cost == t.cost; });
    if (!selected) rest.add_factor(t.cost.get(), t.loss.get(), t.blocks);
  }
  const DenseLinearization full = all.linearize();
  const DenseLinearization other = rest.linearize();
  const Eigen::MatrixXd S = schur(full);

  double* T_WL = s.T_WL.data();
  marginalize_oldest(s);
  ASSERT_TRUE(s.prior);
  const auto& kept = s.prior->parameter_blocks();
  ASSERT_NE(std::find(kept.begin(), kept.end(), T_WL), kept.end()) << "the prior must carry T_WL";
  const Eigen::MatrixXd Hp = s.prior->hessian();
  // Compare block by block: prior(a, b) == S(a, b) - H_other(a, b).
  const auto tangent_of = [&](double* b) {
    return full.tangents[static_cast<std::size_t>(std::find(full.blocks.begin(), full.blocks.end(), b) -
                                                  full.blocks.begin())];
  };
  std::vector<int> prior_offsets;
  int off = 0;
  for (double* b : kept) {
    prior_offsets.push_back(off);
    off += tangent_of(b);
  }
  ASSERT_EQ(off, Hp.rows());
  const int m = full.marginalized_tangent;
  double max_err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    for (std::size_t j = 0; j < kept.size(); ++j) {
      const int ni = tangent_of(kept[i]), nj = tangent_of(kept[j]);
      Eigen::MatrixXd expected = S.block(full.offset_of(kept[i]) - m, full.offset_of(kept[j]) - m, ni, nj);
      const int oi = other.offset_of(kept[i]), oj = other.offset_of(kept[j]);
      if (oi >= 0 && oj >= 0) expected -= other.H.block(oi, oj, ni, nj);
      const Eigen::MatrixXd got = Hp.block(prior_offsets[i], prior_offsets[j], ni, nj);
      max_err = std::max(max_err, (got - expected).cwiseAbs().maxCoeff());
      scale = std::max(scale, expected.cwiseAbs().maxCoeff());
    }
  }
  std::printf("prior vs dense Schur complement: max |diff| %.3g of max entry %.3g\n", max_err, scale);
  EXPECT_LT(max_err, 1e-6 * scale);
  // The provider's information on T_WL is in the prior.
  const int t = prior_offsets[std::find(kept.begin(), kept.end(), T_WL) - kept.begin()];
  EXPECT_GT(Hp.block(t, t, 3, 3).trace(), 0.5);
}

}  // namespace
}  // namespace twinslam::estimator
