// GNSS jumps (gnss_jump.hpp): fixes that step far beyond the vehicle's motion and their own stated sigma are refused
// until the jump is undone or has lasted hold_s; noisy fixes, fast flight and honest large sigmas are never refused.
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/gnss_jump.hpp"

namespace twinslam::estimator {
namespace {

constexpr std::int64_t kFix_ns = 200'000'000;  // 5 Hz

// A straight flight east at `speed` [m/s] with fixes of `sigma` (stated and drawn), 5 Hz; `shift(t)` is added to the
// fix at t [s]. Returns which fixes were accepted.
std::vector<bool> fly(GnssJumpDetector& detector, double seconds, double speed, double sigma,
                      const std::function<Eigen::Vector3d(double)>& shift, bool tracking = true) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Matrix3d cov = sigma * sigma * Eigen::Matrix3d::Identity();
  std::vector<bool> accepted;
  for (int k = 0; k * 0.2 <= seconds; ++k) {
    const double t = 0.2 * k;
    const Eigen::Vector3d truth(speed * t, 0.0, 10.0);
    const Eigen::Vector3d fix = truth + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)) + shift(t);
    // The VIO in its own frame L: turned 90 deg and offset from W (no alignment is needed to compare motions).
    const Eigen::Vector3d p_L(-truth.y() + 3.0, truth.x() - 7.0, truth.z());
    accepted.push_back(detector.accept(k * kFix_ns, fix, cov, tracking ? std::optional(p_L) : std::nullopt));
  }
  return accepted;
}

const auto kNoShift = [](double) { return Eigen::Vector3d::Zero(); };

TEST(GnssJump, NoisyFixesAndFastFlightAreNeverRefused) {
  GnssJumpDetector detector{GnssJumpConfig{}};
  for (bool accepted : fly(detector, 600.0, 30.0, 3.0, kNoShift)) ASSERT_TRUE(accepted);
  EXPECT_EQ(detector.counts().jumps, 0u);
  // Not tracking (no VIO motion to compare with): 4 m between fixes at 20 m/s is still far below a jump.
  GnssJumpDetector blind{GnssJumpConfig{}};
  for (bool accepted : fly(blind, 120.0, 20.0, 1.0, kNoShift, false)) ASSERT_TRUE(accepted);
}

TEST(GnssJump, AFiftyMetreJumpIsRefusedUntilItIsUndone) {
  GnssJumpDetector detector{GnssJumpConfig{}};
  const auto jumped = [](double t) { return t >= 10.0 && t < 15.0; };
  const std::vector<bool> accepted =
      fly(detector, 30.0, 5.0, 2.0, [&](double t) { return Eigen::Vector3d(jumped(t) ? 50.0 : 0.0, 0.0, 0.0); });
  for (std::size_t k = 0; k < accepted.size(); ++k) EXPECT_EQ(accepted[k], !jumped(0.2 * k)) << "fix at " << 0.2 * k;
  EXPECT_EQ(detector.counts().jumps, 1u);
  EXPECT_EQ(detector.counts().undone, 1u);
  EXPECT_EQ(detector.counts().refused, 25u);
  EXPECT_FALSE(detector.jump_open());
}

TEST(GnssJump, AJumpThatLastsBecomesTheNewLevelAfterHoldS) {
  GnssJumpConfig config;
  config.hold_s = 10.0;
  GnssJumpDetector detector{config};
  const std::vector<bool> accepted =
      fly(detector, 40.0, 5.0, 2.0, [](double t) { return Eigen::Vector3d(0.0, t >= 10.0 ? -60.0 : 0.0, 0.0); });
  for (std::size_t k = 0; k < accepted.size(); ++k) {
    const double t = 0.2 * k;
    EXPECT_EQ(accepted[k], t < 10.0 || t > 20.0 + 1e-9) << "fix at " << t;
  }
  EXPECT_EQ(detector.counts().held_out, 1u);
}

TEST(GnssJump, AStepTheReceiverOwnsUpToIsNoJump) {
  // Urban multipath: a 30 m step, but the receiver states 15 m per fix (30 m < 8 x 21 m): used as the receiver says.
  GnssJumpDetector detector{GnssJumpConfig{}};
  const std::vector<bool> accepted =
      fly(detector, 20.0, 5.0, 15.0, [](double t) { return Eigen::Vector3d(t >= 10.0 ? 30.0 : 0.0, 0.0, 0.0); });
  for (bool a : accepted) EXPECT_TRUE(a);
  GnssJumpConfig off;
  off.jump_sigmas = 0.0;
  GnssJumpDetector none{off};
  for (bool a : fly(none, 20.0, 5.0, 1.0, [](double t) { return Eigen::Vector3d(t >= 10.0 ? 90.0 : 0.0, 0, 0); })) {
    EXPECT_TRUE(a);
  }
}

TEST(GnssJump, BadConfigIsNamed) {
  GnssJumpConfig c;
  c.hold_s = -1.0;
  try {
    c.validate();
    FAIL() << "accepted a negative hold";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "global fusion: gnss_jump_hold_s must be >= 0");
  }
}

}  // namespace
}  // namespace twinslam::estimator
