// GlobalFusion (global_fusion.hpp): the GNSS alignment after a registration outage replaces the estimate only when
// the fit is more certain than the estimate; readmitted registrations reopen a wrong alignment; GNSS fixes in the
// window and the loose graph; registrations the estimator cannot or must not fuse. Declaring the alignment:
// test_world_declaration.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "global_fusion_flight.hpp"
#include "position_provider.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/global_fusion.hpp"
#include "twinslam/geometry/se3.hpp"

namespace twinslam::estimator {
namespace {

using testing::feed_imu;
using testing::flight;
using testing::SimRun;
using testing::window_config;

// Flies the run with a GNSS fix (true position + 1 m noise per axis, L = W) every fourth frame and no registration at
// all, so every realign_after_s an outage asks for a new alignment. With `anchored`, another W-frame source (5 cm
// position factors on every frame, standing in for what keeps a real estimate certain) is in the window too.
GlobalFusionCounts fly(const SimRun& run, bool anchored) {
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.fuse_registrations = true;
  g.align_from_gnss = true;
  g.realign_after_s = 5.0;
  g.gnss_correlation_s = 0.0;  // white-noise fixes: independent
  GlobalFusion fusion(est, g);
  auto anchor = std::make_shared<testing::PositionProvider>();
  if (anchored) est.add_factor_provider(anchor);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  est.initialize_next_frame(run.frames.front().truth);
  std::size_t imu_next = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    const auto& f = run.frames[k];
    feed_imu(run, est, imu_next, f.stamp_ns);
    anchor->add_fix(f.stamp_ns, f.truth.p_L, 0.05);
    if (k % 4 == 0) {
      fusion.on_gnss(f.stamp_ns, f.truth.p_L + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)),
                     Eigen::Matrix3d::Identity());
    }
    const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
    fusion.after_frame(e, est.local_map());
  }
  return fusion.counts();
}

TEST(GlobalFusion, RealignsAfterAnOutageOnlyWhenTheGnssFitIsMoreCertainThanTheEstimate) {
  const SimRun run = flight();
  // GNSS alone: the estimate in W is as uncertain as the first short fit, and later fits over a longer path beat it.
  const GlobalFusionCounts gnss_only = fly(run, false);
  EXPECT_GE(gnss_only.alignments, 2u);
  // The estimate is held to 5 cm by another source: no fit of 1 m fixes beats it, so none replaces it.
  const GlobalFusionCounts anchored = fly(run, true);
  EXPECT_EQ(anchored.alignments - anchored.provisional_alignments, 1u);  // the converged fit, never replaced
  EXPECT_GE(anchored.realignments_declined, 1u);
}


// Flies `run` (from its first true state) through `est` and `fusion`. For every LocalMap published once T_WL is set,
// from 1 s on (the first one was published before an initial pose set T_WL), `on_keyframe(t, map, true T_WB)`; after
// every frame `after(t, estimate, frame)`, which returns false to stop.
void fly_registering(const SimRun& run, SlidingWindowEstimator& est, GlobalFusion& fusion,
                     const std::function<void(double, const LocalMapEstimate&, const Eigen::Isometry3d&)>& on_keyframe,
                     const std::function<bool(double, const FrameEstimate&, const testing::SimFrame&)>& after) {
  est.initialize_next_frame(run.frames.front().truth);
  std::size_t imu_next = 0;
  for (const auto& f : run.frames) {
    const double t = 1e-9 * static_cast<double>(f.stamp_ns - run.frames.front().stamp_ns);
    feed_imu(run, est, imu_next, f.stamp_ns);
    const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
    fusion.after_frame(e, est.local_map());
    if (const auto& map = est.local_map(); map && est.world_aligned() && t >= 1.0) {
      on_keyframe(t, *map, geometry::make_pose(f.truth.q_LB, f.truth.p_L));
    }
    if (!after(t, e, f)) return;
  }
}

// A heading 4 deg off (or heading_error_deg), held by an overconfident prior (0.5 deg), and registrations that agree with it (identity
// corrections: ICP settled near the wrong estimate) for the first 12 s. Then one registration of the true pose comes
// with `readmitted` as registration's persistence gate sends it, and registrations of the true pose follow, accepted
// only while they are small (0.5 deg, 0.5 m: the prior's sigmas), as registration's Mahalanobis test does. Returns the
// heading error of T_WL 1 s after the re-admitted registration [deg] and the fusion counts.
struct Reopened {
  double yaw_error_deg = 0.0;
  GlobalFusionCounts counts;
  MapRegistrationCounts registrations;
};
Reopened fly_wrong_heading(const SimRun& run, bool realign, double heading_error_deg = 4.0) {
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.fuse_registrations = true;
  g.realign_on_readmitted_registration = realign;
  g.initial_pose_yaw_sigma_deg = 0.5;
  const auto& first = run.frames.front().truth;
  const Eigen::Matrix3d R0 = first.q_LB.toRotationMatrix();
  InitialPose start{first.p_L, std::atan2(R0(1, 0), R0(0, 0)) * 180.0 / M_PI + heading_error_deg, std::nullopt};
  GlobalFusion fusion(est, g, start);
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  information.diagonal() << Eigen::Vector3d::Constant(std::pow(180.0 / M_PI / 0.2, 2)), Eigen::Vector3d::Constant(100.0);
  std::optional<std::int64_t> readmitted_ns;
  Reopened out;
  fly_registering(
      run, est, fusion,
      [&](double t, const LocalMapEstimate& map, const Eigen::Isometry3d& truth) {
        const bool wrong = t < 12.0;
        const bool readmit = !wrong && !readmitted_ns;
        const Eigen::Isometry3d correction =
            wrong ? Eigen::Isometry3d::Identity() : Eigen::Isometry3d(truth * (map.T_WL * map.T_LB).inverse());
        const double dyaw_deg =
            std::abs(std::atan2(correction.linear()(1, 0), correction.linear()(0, 0))) * 180.0 / M_PI;
        const bool plausible = dyaw_deg < 0.5 && (correction * truth.translation() - truth.translation()).norm() < 0.5;
        fusion.on_registration(map.keyframe_stamp_ns, wrong || readmit || plausible, correction, information, readmit);
        if (readmit) readmitted_ns = map.keyframe_stamp_ns;
      },
      [&](double, const FrameEstimate&, const testing::SimFrame& f) {
        if (!readmitted_ns || f.stamp_ns < *readmitted_ns + 1'000'000'000LL) return true;
        const Eigen::Matrix3d R = est.world_alignment().linear();
        out.yaw_error_deg = std::abs(std::atan2(R(1, 0), R(0, 0))) * 180.0 / M_PI;
        return false;
      });
  out.counts = fusion.counts();
  out.registrations = fusion.registration_counts();
  return out;
}

// A re-admitted registration re-opens the alignment: T_WL jumps to the heading the twin gives, the registrations that
// agreed with the wrong estimate leave the window, and the heading is right at once (0.02 deg measured). Without it,
// the same registration is one Huber-weighted term against those registrations and the prior: 3.8 deg off after 1 s.
TEST(GlobalFusion, AReadmittedRegistrationReopensAWrongAlignment) {
  const SimRun run = flight();
  const Reopened reopened = fly_wrong_heading(run, true);
  EXPECT_EQ(reopened.counts.registration_realignments, 1u);
  EXPECT_GT(reopened.registrations.dropped, 5u);
  EXPECT_LT(reopened.yaw_error_deg, 0.2);
  const Reopened held = fly_wrong_heading(run, false);
  EXPECT_EQ(held.counts.registration_realignments, 0u);
  EXPECT_EQ(held.registrations.dropped, 0u);
  EXPECT_GT(held.yaw_error_deg, 2.0);
}

// A re-admitted correction within what one registration resolves (here 0.5 deg, realign_min_correction_* 1 m / 1 deg)
// is fused like any other: re-opening would drop the registrations that hold the estimate for nothing.
TEST(GlobalFusion, ASmallReadmittedCorrectionIsFusedWithoutReopening) {
  const SimRun run = flight();
  const Reopened small = fly_wrong_heading(run, true, 0.5);
  EXPECT_EQ(small.counts.registration_realignments, 0u);
  EXPECT_EQ(small.registrations.dropped, 0u);
  EXPECT_GT(small.counts.registrations_accepted, 10u);
}

// Flies the figure-eight with a fix (truth + 1 m white noise) every 4th frame through GlobalFusion configured by `g`.
// Returns the RMS position error in W over the last 10 s of frames where `T_WL` (read after each frame) has a value,
// and how many fixes were sent. Truth: L = W.
struct NoisyFixFlight {
  double rms_m = 0;
  int frames = 0;
  std::size_t fixes = 0;
};
NoisyFixFlight fly_with_noisy_fixes(
    const SimRun& run, GlobalFusion& fusion, SlidingWindowEstimator& est,
    const std::function<std::optional<Eigen::Isometry3d>(std::size_t)>& T_WL) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  est.initialize_next_frame(run.frames.front().truth);
  std::size_t imu_next = 0;
  NoisyFixFlight out;
  double sq = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    const auto& f = run.frames[k];
    feed_imu(run, est, imu_next, f.stamp_ns);
    if (k % 4 == 0) {
      fusion.on_gnss(f.stamp_ns, f.truth.p_L + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)),
                     Eigen::Matrix3d::Identity());
      ++out.fixes;
    }
    const FrameEstimate e = est.add_frame(f.stamp_ns, f.features);
    fusion.after_frame(e, est.local_map());
    const std::optional<Eigen::Isometry3d> alignment = T_WL(k);
    if (alignment && f.stamp_ns > run.frames.back().stamp_ns - 10'000'000'000LL) {
      sq += ((*alignment * e.T_LB).translation() - f.truth.p_L).squaredNorm();
      ++out.frames;
    }
  }
  if (out.frames > 0) out.rms_m = std::sqrt(sq / out.frames);
  return out;
}

// vio-gnss on the figure-eight: fixes align T_WL and then act as window terms. After the declaration the estimate in W
// stays on the truth, and every fix is accounted for (fused, or counted unmatched).
TEST(GlobalFusion, FusedGnssFixesHoldTheEstimateInTheWorldFrame) {
  const SimRun run = flight();
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.align_from_gnss = true;
  g.fuse_gnss = true;
  g.gnss_correlation_s = 0.0;  // white-noise fixes
  GlobalFusion fusion(est, g);
  const NoisyFixFlight r = fly_with_noisy_fixes(run, fusion, est, [&](std::size_t) {
    return fusion.world_declared() ? std::optional<Eigen::Isometry3d>(est.world_alignment()) : std::nullopt;
  });
  ASSERT_GT(r.frames, 0) << "never declared";
  EXPECT_LT(r.rms_m, 0.5);  // 1 m fixes averaged by the window and the prior
  const GnssProviderCounts& c = fusion.gnss_counts();
  EXPECT_EQ(c.received, r.fixes);
  EXPECT_GT(c.attached, r.fixes / 2);
  EXPECT_GT(c.marginalized, 0u);
}

// vio-gnss-loose on the figure-eight: the same fixes go to the pose graph apart from the window. Once declared, the
// published alignment is the graph's, its poses stay on the truth, and the window never sees a GNSS term.
TEST(GlobalFusion, LooseGnssGraphPublishesItsOwnAlignmentAndLeavesTheWindowAlone) {
  const SimRun run = flight();
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.align_from_gnss = true;
  g.fuse_gnss_loose = true;
  g.gnss_correlation_s = 0.0;  // white-noise fixes
  GlobalFusion fusion(est, g);
  const NoisyFixFlight r = fly_with_noisy_fixes(run, fusion, est, [&](std::size_t k) {
    EXPECT_EQ(fusion.output_T_WL().has_value(), fusion.world_declared()) << "frame " << k;
    return fusion.output_T_WL();
  });
  ASSERT_GT(r.frames, 0) << "never declared";
  EXPECT_LT(r.rms_m, 0.6);
  EXPECT_EQ(fusion.gnss_counts().attached, 0u);  // nothing in the window
  EXPECT_GT(fusion.loose_counts().solves, 10u);
  EXPECT_GT(fusion.loose_counts().fixes_used, 40u);
}

// A registration service that goes wrong mid-flight (issue 15: "a registration correction 20 m off"): from 10 to 14 s
// every accepted registration puts the keyframe 20 m east of the truth. The estimator's own gate refuses each one
// against the covariance it published with the LocalMap and counts it, and a refused registration has no effect at all:
// the estimate is the same, bit for bit, as when those registrations never arrive.
struct GatedFlight {
  std::vector<Eigen::Vector3d> p_W;  // the estimate in W per frame once declared
  GlobalFusionCounts counts;
  unsigned long long faulty = 0;  // registrations sent 20 m off
  double worst_m = 0.0;           // largest position error in W
};
GatedFlight fly_with_faulty_registrations(const SimRun& run, bool send_faulty) {
  SlidingWindowEstimator est(window_config(run));
  GlobalFusionConfig g;
  g.fuse_registrations = true;
  g.initial_pose_yaw_sigma_deg = 1.0;  // declared at once
  g.initial_pose_position_sigma_m = 0.5;
  const auto& first = run.frames.front().truth;
  const Eigen::Matrix3d R0 = first.q_LB.toRotationMatrix();
  GlobalFusion fusion(est, g, InitialPose{first.p_L, std::atan2(R0(1, 0), R0(0, 0)) * 180.0 / M_PI, std::nullopt});
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  information.diagonal() << Eigen::Vector3d::Constant(std::pow(180.0 / M_PI / 0.5, 2)), Eigen::Vector3d::Constant(25.0);
  GatedFlight out;
  fly_registering(
      run, est, fusion,
      [&](double t, const LocalMapEstimate& map, const Eigen::Isometry3d& truth) {
        EXPECT_TRUE(fusion.published_covariance(map.keyframe_stamp_ns).has_value()) << "at " << t << " s";
        Eigen::Isometry3d correction(truth * (map.T_WL * map.T_LB).inverse());
        const bool fault = t >= 10.0 && t < 14.0;
        if (fault) correction.pretranslate(Eigen::Vector3d(20.0, 0.0, 0.0));
        out.faulty += fault;
        if (fault && !send_faulty) return;
        const std::string why = fusion.on_registration(map.keyframe_stamp_ns, true, correction, information);
        EXPECT_EQ(why.empty(), !fault) << "at " << t << " s: " << why;
      },
      [&](double, const FrameEstimate& e, const testing::SimFrame& f) {
        if (fusion.world_declared()) {
          out.p_W.push_back((est.world_alignment() * e.T_LB).translation());
          out.worst_m = std::max(out.worst_m, (out.p_W.back() - f.truth.p_L).norm());
        }
        return true;
      });
  out.counts = fusion.counts();
  return out;
}

TEST(GlobalFusion, RegistrationsTwentyMetresOffAreRefusedByTheEstimatorsOwnGate) {
  const SimRun run = flight();
  const GatedFlight faulty = fly_with_faulty_registrations(run, true);
  EXPECT_GT(faulty.faulty, 3u);
  EXPECT_EQ(faulty.counts.registrations_refused, faulty.faulty);
  EXPECT_GT(faulty.counts.registrations_accepted, 20u);
  EXPECT_LT(faulty.worst_m, 1.0);
  const GatedFlight without = fly_with_faulty_registrations(run, false);
  EXPECT_EQ(without.counts.registrations_refused, 0u);
  EXPECT_EQ(faulty.p_W, without.p_W);  // refused = never arrived
}

TEST(GlobalFusion, LooseAndTightGnssExcludeEachOther) {
  GlobalFusionConfig g;
  g.align_from_gnss = true;
  g.fuse_gnss = true;
  g.fuse_gnss_loose = true;
  EXPECT_THROW(g.validate(), InputError);
  g.fuse_gnss = false;
  EXPECT_NO_THROW(g.validate());
  g.align_from_gnss = false;
  EXPECT_THROW(g.validate(), InputError);
}

}  // namespace
}  // namespace twinslam::estimator

namespace twinslam::estimator {
namespace {

// A registration that registration accepted but that cannot be fused (NaN information, a broken correction) is
// counted as invalid and never reaches the window, however the fusion stands.
TEST(GlobalFusion, AnUnfusableRegistrationIsCountedAndDropped) {
  SlidingWindowEstimator est{SlidingWindowConfig{}};
  GlobalFusionConfig g;
  g.fuse_registrations = true;
  GlobalFusion fusion(est, g);
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Identity();
  information(0, 0) = NAN;
  fusion.on_registration(1'000, true, Eigen::Isometry3d::Identity(), information);
  information(0, 0) = 1.0;
  information(0, 1) = 0.5;  // not symmetric
  fusion.on_registration(2'000, true, Eigen::Isometry3d::Identity(), information);
  EXPECT_EQ(fusion.counts().registrations_in, 2u);
  EXPECT_EQ(fusion.counts().registrations_invalid, 2u);
  EXPECT_EQ(fusion.counts().registrations_before_alignment, 0u);  // refused before anything else looked at it
  EXPECT_EQ(fusion.counts().registrations_accepted, 0u);
}

}  // namespace
}  // namespace twinslam::estimator
