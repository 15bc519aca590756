// ScaleTracker: the per-vehicle scale prior starts with the first accepted registration, loosens with time between
// registrations (the random walk), tightens with each accepted one, and ignores rejected ones and nonsense scales.
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

}  // namespace
}  // namespace twinslam::registration
