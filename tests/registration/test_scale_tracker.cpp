// ScaleTracker: the per-vehicle scale prior starts with the first accepted registration, loosens with time between
// registrations (the random walk), tightens with each accepted one, and ignores rejected ones and nonsense scales;
// scale_prior_applies: it applies only to keyframes the estimator is settled on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "twinslam/registration/scale_tracker.hpp"

namespace twinslam::registration {
namespace {

std::int64_t at(double t_s) { return static_cast<std::int64_t>(t_s * 1e9); }

RegistrationConfig with_walk(double walk) {
  RegistrationConfig c;
  c.scale_prior_walk = walk;
  c.scale_prior_measurement_sigma = 0.01;
  return c;
}

TEST(RegistrationScaleTracker, NoPriorBeforeTheFirstAcceptedRegistration) {
  ScaleTracker t(with_walk(0.002));
  EXPECT_FALSE(t.prior(at(1)));
  t.update(at(1), false, 1.05);  // rejected: not a measurement
  EXPECT_FALSE(t.prior(at(2)));
  t.update(at(2), true, 1.02);
  const auto p = t.prior(at(2));
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->log_scale, std::log(1.02), 1e-12);
  EXPECT_NEAR(p->sigma, 0.01, 1e-12);  // one measurement: its own sigma
}

TEST(RegistrationScaleTracker, LoosensWithTimeAndTightensWithRegistrations) {
  ScaleTracker t(with_walk(0.002));
  t.update(at(0), true, 1.0);
  // 100 s without a registration: variance 0.01^2 + 0.002^2 x 100.
  EXPECT_NEAR(t.prior(at(100))->sigma, std::sqrt(1e-4 + 4e-4), 1e-12);
  EXPECT_NEAR(t.prior(at(-100))->sigma, std::sqrt(1e-4 + 4e-4), 1e-12);  // out of order: by |dt|
  double last = t.prior(at(0))->sigma;
  for (int k = 1; k <= 20; ++k) {
    t.update(at(0.5 * k), true, 1.01);
    const double now = t.prior(at(0.5 * k))->sigma;
    EXPECT_LT(now, last);
    last = now;
  }
  // Steady state near sqrt(q R) with q = walk^2 dt: far tighter than one registration, never zero.
  EXPECT_LT(last, 0.005);
  EXPECT_GT(last, 0.001);
  EXPECT_NEAR(t.prior(at(10))->log_scale, std::log(1.01), 1e-12);
}

TEST(RegistrationScaleTracker, RejectedAndNonsenseScalesDoNotMoveIt) {
  ScaleTracker t(with_walk(0.002));
  t.update(at(0), true, 1.0);
  t.update(at(1), false, 0.9);
  t.update(at(2), true, std::nan(""));
  t.update(at(3), true, 0.0);
  t.update(at(4), true, -1.0);
  EXPECT_NEAR(t.prior(at(4))->log_scale, 0.0, 1e-12);
}

TEST(RegistrationScaleTracker, OffWithoutAWalkOrWithoutScale) {
  ScaleTracker off(with_walk(0.0));
  off.update(at(0), true, 1.02);
  EXPECT_FALSE(off.prior(at(1)));
  RegistrationConfig rigid = with_walk(0.002);
  rigid.estimate_scale = false;
  ScaleTracker t(rigid);
  t.update(at(0), true, 1.0);
  EXPECT_FALSE(t.prior(at(1)));
}

// A keyframe covariance (rotation first) with the given heading sigma about W's z and position sigma per axis.
Matrix6d keyframe_covariance(double heading_sigma_deg, double position_sigma_per_axis_m) {
  Matrix6d P = Matrix6d::Zero();
  const double h = heading_sigma_deg * M_PI / 180.0;
  P.diagonal() << 1e-6, 1e-6, h * h, Eigen::Vector3d::Constant(position_sigma_per_axis_m * position_sigma_per_axis_m);
  return P;
}

TEST(RegistrationScaleTracker, AppliesOnlyOnceTheEstimatorHasSettled) {
  RegistrationConfig c = with_walk(0.003);
  c.scale_prior_max_heading_sigma_deg = 0.25;
  c.scale_prior_max_position_sigma_m = 0.25;
  // delft-loops at 18 s (the GNSS alignment just declared, twin corrections being fused): not yet ...
  EXPECT_FALSE(scale_prior_applies(c, keyframe_covariance(0.41, 0.16)));
  // ... position sigma 0.4 m (sqrt of the trace: 0.23 m per axis) with a good heading: not yet either ...
  EXPECT_FALSE(scale_prior_applies(c, keyframe_covariance(0.1, 0.23)));
  // ... at 28 s, settled: heading 0.22 deg, position 0.18 m.
  EXPECT_TRUE(scale_prior_applies(c, keyframe_covariance(0.22, 0.18 / std::sqrt(3.0))));
  // No covariance sent, or one that is not a number: never.
  EXPECT_FALSE(scale_prior_applies(c, std::nullopt));
  Matrix6d nan = keyframe_covariance(0.1, 0.05);
  nan(2, 2) = std::nan("");
  EXPECT_FALSE(scale_prior_applies(c, nan));
  nan = keyframe_covariance(0.1, 0.05);
  nan(4, 4) = std::nan("");
  EXPECT_FALSE(scale_prior_applies(c, nan));
}

}  // namespace
}  // namespace twinslam::registration
