// GlobalFusion (global_fusion.hpp) declaring the world alignment: a provisional GNSS alignment is declared once
// registrations have made the heading certain and agree with the estimate; GNSS fixes with correlated errors do not
// declare an overconfident heading.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "global_fusion_flight.hpp"
#include "twinslam/estimator/global_fusion.hpp"
#include "twinslam/geometry/se3.hpp"

namespace twinslam::estimator {
namespace {

using testing::feed_imu;
using testing::flight;
using testing::SimRun;
using testing::window_config;

struct Declaration {
  std::optional<double> provisional_s, declared_s;  // since the first frame
  double yaw_error_deg = 0.0;                       // of T_WL when declared (truth: L = W)
  bool declared_before_registration = false;
  bool declared_by_gnss_fit = false;  // in the step that set T_WL from a converged GNSS fit (not by registrations)
};

// A GNSS fix (true position + 1 m noise per axis, L = W) every fourth frame; with `registrations`, every keyframe's
// LocalMap is answered by a registration of the true pose (0.05 m, 0.1 deg, information times `information_scale`) as
// soon as T_WL is set, provisionally or not.
// With `alternate_m`, successive registrations put their keyframes alternately that far east and west of the truth
// (ICP flipping between two solutions); `agreeing` is declare_agreeing_registrations.
Declaration declare(const SimRun& run, bool registrations, double information_scale = 1.0, double alternate_m = 0.0,
                    int agreeing = GlobalFusionConfig{}.declare_agreeing_registrations) {
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.fuse_registrations = true;
  g.align_from_gnss = true;
  g.gnss_correlation_s = 0.0;  // white-noise fixes: independent
  g.declare_agreeing_registrations = agreeing;
  GlobalFusion fusion(est, g);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  est.initialize_next_frame(run.frames.front().truth);
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  information.diagonal() << Eigen::Vector3d::Constant(std::pow(180.0 / M_PI / 0.1, 2)), Eigen::Vector3d::Constant(400.0);
  information *= information_scale;
  Declaration out;
  std::size_t imu_next = 0, registrations_sent = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    const auto& f = run.frames[k];
    const double t = 1e-9 * static_cast<double>(f.stamp_ns - run.frames.front().stamp_ns);
    feed_imu(run, est, imu_next, f.stamp_ns);
    const auto alignments_before = fusion.counts().alignments;
    if (k % 4 == 0) {
      fusion.on_gnss(f.stamp_ns, f.truth.p_L + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)),
                     Eigen::Matrix3d::Identity());
    }
    const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
    fusion.after_frame(e, est.local_map());
    if (!out.provisional_s && fusion.counts().alignments > 0) out.provisional_s = t;
    if (!out.declared_s && fusion.world_declared()) {
      out.declared_s = t;
      out.declared_before_registration = fusion.counts().registrations_accepted == 0;
      out.declared_by_gnss_fit = fusion.counts().alignments > alignments_before;
      const Eigen::Matrix3d R = est.world_alignment().linear();
      out.yaw_error_deg = std::abs(std::atan2(R(1, 0), R(0, 0))) * 180.0 / M_PI;
    }
    const auto& map = est.local_map();
    if (registrations && map && est.world_aligned()) {
      Eigen::Isometry3d truth = geometry::make_pose(f.truth.q_LB, f.truth.p_L);
      truth.translation().x() += (registrations_sent++ % 2 == 0 ? alternate_m : -alternate_m);
      const Eigen::Isometry3d correction = truth * (map->T_WL * map->T_LB).inverse();
      fusion.on_registration(map->keyframe_stamp_ns, true, correction, information);
    }
  }
  return out;
}

TEST(GlobalFusion, AProvisionalGnssAlignmentIsDeclaredOnceRegistrationsMakeTheHeadingCertain) {
  const SimRun run = flight();
  // GNSS alone: T_WL is set provisionally (heading sigma < 30 deg) but declared only when the fit converges (3 deg).
  const Declaration gnss = declare(run, false);
  ASSERT_TRUE(gnss.provisional_s && gnss.declared_s);
  EXPECT_LT(*gnss.provisional_s, *gnss.declared_s);
  EXPECT_TRUE(gnss.declared_before_registration);
  // With registrations from the provisional alignment on: declared at the keyframe after the third one (three agree
  // with the estimate: declare_agreeing_registrations), here no later than the quick GNSS fit of independent 1 m
  // fixes, and the heading is then that of the registrations.
  const Declaration reg = declare(run, true);
  ASSERT_TRUE(reg.provisional_s && reg.declared_s);
  EXPECT_DOUBLE_EQ(*reg.provisional_s, *gnss.provisional_s);
  EXPECT_LT(*reg.declared_s, *reg.provisional_s + 1.5);
  EXPECT_LE(*reg.declared_s, *gnss.declared_s);
  EXPECT_FALSE(reg.declared_before_registration);
  EXPECT_LT(reg.yaw_error_deg, 0.3);
  // Registrations too weak to make the heading certain (eq. 10's weights can be): the converged GNSS fit still
  // declares it, no later than GNSS alone.
  const Declaration weak = declare(run, true, 1e-9);
  ASSERT_TRUE(weak.declared_s);
  EXPECT_FALSE(weak.declared_before_registration);
  EXPECT_LE(*weak.declared_s, *gnss.declared_s);
}

// Registrations that keep moving the keyframes by metres (here alternating 4 m east and west of the truth, each with
// the full 0.05 m information) make the window's heading sigma small, yet the estimate is not where they put it: the
// alignment is not declared from them (declare_agreeing_registrations), only by the GNSS fit once it converges.
TEST(GlobalFusion, RegistrationsThatKeepMovingTheKeyframeByMetresDoNotDeclareTheAlignment) {
  const SimRun run = flight();
  const Declaration gnss = declare(run, false);
  ASSERT_TRUE(gnss.declared_s);
  EXPECT_TRUE(gnss.declared_by_gnss_fit);
  const Declaration heading_only = declare(run, true, 1.0, 4.0, 0);
  ASSERT_TRUE(heading_only.declared_s);
  EXPECT_FALSE(heading_only.declared_before_registration);
  EXPECT_FALSE(heading_only.declared_by_gnss_fit);        // on the heading sigma alone: declared at once
  EXPECT_LT(*heading_only.declared_s, *gnss.declared_s);
  // With the rule: only a converged GNSS fit declares. Not "no earlier than GNSS alone": the registrations move the
  // estimate the fixes are paired with, so that fit may converge a little earlier or later (it did, built with clang).
  const Declaration agreeing = declare(run, true, 1.0, 4.0);
  EXPECT_TRUE(!agreeing.declared_s || agreeing.declared_by_gnss_fit)
      << "declared at " << *agreeing.declared_s << " s by registrations 4 m off";
}

// GNSS whose error is a slowly varying bias (urban NLOS, atmosphere): the track rotated by 8 deg about its start plus
// 0.3 m of white noise. Taken as independent, 1 m fixes declare a fit whose heading is degrees off; counting one fix
// per 30 s (gnss_correlation_s) keeps the fit's heading sigma honest, so it is not declared within the 30 s flight.
std::optional<double> declared_heading_error_deg(const SimRun& run, double correlation_s) {
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.align_from_gnss = true;
  g.gnss_correlation_s = correlation_s;
  GlobalFusion fusion(est, g);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.3);
  const Eigen::AngleAxisd bias(8.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d start = run.frames.front().truth.p_L;
  est.initialize_next_frame(run.frames.front().truth);
  std::size_t imu_next = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    const auto& f = run.frames[k];
    feed_imu(run, est, imu_next, f.stamp_ns);
    if (k % 4 == 0) {
      const Eigen::Vector3d p = start + bias * (f.truth.p_L - start) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      fusion.on_gnss(f.stamp_ns, p, Eigen::Matrix3d::Identity());
    }
    const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
    fusion.after_frame(e, est.local_map());
    if (fusion.world_declared()) {
      const Eigen::Matrix3d R = est.world_alignment().linear();
      return std::abs(std::atan2(R(1, 0), R(0, 0))) * 180.0 / M_PI;
    }
  }
  return std::nullopt;
}

TEST(GlobalFusion, CorrelatedGnssErrorsDoNotDeclareAnOverconfidentHeading) {
  const SimRun run = flight();
  const std::optional<double> independent = declared_heading_error_deg(run, 0.0);
  ASSERT_TRUE(independent.has_value());
  EXPECT_GT(*independent, 3.0);  // declared (sigma < 3 deg) with a heading error larger than that
  EXPECT_FALSE(declared_heading_error_deg(run, 30.0).has_value());
}

}  // namespace
}  // namespace twinslam::estimator
