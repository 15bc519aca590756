// The receiver: exact pseudoranges give the exact position from far away, an injected fault is excluded, too few
// satellites give no fix, and the covariance scales with the stated noise.
#include <gtest/gtest.h>

#include <random>

#include "twinslam/gnss/constellation.hpp"
#include "twinslam/gnss/fde.hpp"
#include "twinslam/gnss/frames.hpp"
#include "twinslam/gnss/orbit.hpp"
#include "twinslam/gnss/receiver.hpp"

namespace twinslam::gnss {
namespace {

const Eigen::Vector3d kReceiver = geodetic_to_ecef({52.5094, 13.3762, 75.0});  // Potsdamer Platz

// Pseudoranges of every satellite above 10 deg: geometric range + receiver clock (one offset per system) + noise.
Epoch simulate_epoch(double t_s, double noise_m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  Epoch e;
  e.t_s = t_s;
  const std::vector<OrbitElements> almanac = nominal_constellation();
  for (const SatelliteInView& s : satellites_in_view(almanac, kReceiver, t_s, 10)) {
    const auto it = std::find_if(almanac.begin(), almanac.end(),
                                 [&](const OrbitElements& o) { return o.id == s.id && o.system == s.system; });
    const SignalGeometry g = signal_geometry(*it, kReceiver, t_s);
    Pseudorange p;
    p.satellite_id = s.id;
    p.system = s.system;
    p.satellite_ecef = g.sat_ecef;
    p.elevation_deg = s.elevation_deg;
    p.cn0_dbhz = 48;
    p.sigma_m = noise_m > 0 ? noise_m : 1.0;
    const double clock_m = s.system == SatSystem::kGps ? 12345.678 : -2222.5;
    p.range_m = g.range_m + clock_m + noise_m * n(rng);
    e.observations.push_back(p);
  }
  return e;
}

TEST(GnssReceiver, ExactPseudorangesGiveTheTruthFromAThousandKilometresAway) {
  const Epoch e = simulate_epoch(3600, 0, 1);
  ASSERT_GE(e.observations.size(), 8u);
  const Eigen::Vector3d guess = kReceiver + Eigen::Vector3d(600e3, -500e3, 624.5e3);  // ~1000 km off
  ASSERT_GT((guess - kReceiver).norm(), 999e3);
  const Fix f = solve_fix(e, guess, ReceiverConfig{});
  ASSERT_TRUE(f.valid) << f.reason;
  EXPECT_LT((f.p_ecef - kReceiver).norm(), 1e-3);
  EXPECT_TRUE(f.excluded.empty());
  ASSERT_EQ(f.clock_systems.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(f.clock_m[k], f.clock_systems[k] == SatSystem::kGps ? 12345.678 : -2222.5, 1e-3);
  }
  // And from the Earth's centre, the receiver's own start when it has no fix yet.
  EXPECT_LT((solve_fix(e, Eigen::Vector3d::Zero(), ReceiverConfig{}).p_ecef - kReceiver).norm(), 1e-3);
}

TEST(GnssReceiver, WithoutEarthRotationTheFixIsMetresOff) {
  // The Sagnac correction matters: the same data solved without it lands metres away.
  const Epoch e = simulate_epoch(3600, 0, 1);
  ReceiverConfig c;
  c.earth_rotation = false;
  const Fix f = solve_fix(e, Eigen::Vector3d::Zero(), c);
  ASSERT_TRUE(f.valid);
  EXPECT_GT((f.p_ecef - kReceiver).norm(), 1.0);
}

TEST(GnssReceiver, ExclusionRemovesAnInjected100mFault) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    Epoch e = simulate_epoch(600.0 * static_cast<double>(seed), 1.0, seed);
    ASSERT_GE(e.observations.size(), 8u);
    const std::size_t faulty = seed % e.observations.size();
    e.observations[faulty].range_m += 100;
    ReceiverConfig no_fde;
    no_fde.max_exclusions = 0;
    const Fix raw = solve_fix(e, Eigen::Vector3d::Zero(), no_fde);
    ASSERT_TRUE(raw.valid);
    EXPECT_FALSE(raw.residual_test_passed) << "seed " << seed;
    const Fix f = solve_fix(e, Eigen::Vector3d::Zero(), ReceiverConfig{});
    ASSERT_TRUE(f.valid);
    ASSERT_EQ(f.excluded.size(), 1u) << "seed " << seed;
    EXPECT_EQ(f.excluded[0], static_cast<int>(faulty)) << "seed " << seed;
    EXPECT_TRUE(f.residual_test_passed);
    EXPECT_LT((f.p_ecef - kReceiver).norm(), 10.0);
    EXPECT_LT((f.p_ecef - kReceiver).norm(), (raw.p_ecef - kReceiver).norm());
  }
}

TEST(GnssReceiver, NoFixWithFewerSatellitesThanUnknowns) {
  Epoch e = simulate_epoch(3600, 0, 1);
  std::vector<Pseudorange> gps;
  for (const Pseudorange& p : e.observations) {
    if (p.system == SatSystem::kGps) gps.push_back(p);
  }
  ASSERT_GE(gps.size(), 4u);
  e.observations.assign(gps.begin(), gps.begin() + 3);
  const Fix f = solve_fix(e, Eigen::Vector3d::Zero(), ReceiverConfig{});
  EXPECT_FALSE(f.valid);
  EXPECT_NE(f.reason.find("3 satellites for 4 unknowns"), std::string::npos) << f.reason;
  e.observations.assign(gps.begin(), gps.begin() + 4);  // exactly determined: a fix, nothing to test
  const Fix g = solve_fix(e, Eigen::Vector3d::Zero(), ReceiverConfig{});
  ASSERT_TRUE(g.valid) << g.reason;
  EXPECT_LT((g.p_ecef - kReceiver).norm(), 1e-3);
}

TEST(GnssReceiver, CovarianceMatchesTheScatterOfNoisyFixes) {
  // 200 epochs with 2 m noise: the stated horizontal variance equals the observed one within 25 %.
  std::vector<Eigen::Vector3d> errors;
  Eigen::Matrix3d stated = Eigen::Matrix3d::Zero();
  for (std::uint64_t k = 0; k < 200; ++k) {
    const Epoch e = simulate_epoch(3600, 2.0, 100 + k);  // same geometry, new noise
    ReceiverConfig c;
    c.max_exclusions = 0;
    const Fix f = solve_fix(e, Eigen::Vector3d::Zero(), c);
    ASSERT_TRUE(f.valid);
    errors.push_back(f.p_ecef - kReceiver);
    stated = f.cov_ecef;
  }
  Eigen::Matrix3d observed = Eigen::Matrix3d::Zero();
  for (const auto& d : errors) observed += d * d.transpose() / static_cast<double>(errors.size());
  EXPECT_NEAR(observed.trace() / stated.trace(), 1.0, 0.25);
}

TEST(GnssReceiver, ChiSquareQuantileHasTheTabulatedValues) {
  EXPECT_NEAR(chi_square_quantile(1, 0.05), 3.841, 1e-3);
  EXPECT_NEAR(chi_square_quantile(5, 0.001), 20.515, 1e-3);
  EXPECT_NEAR(chi_square_quantile(10, 0.01), 23.209, 1e-3);
}

}  // namespace
}  // namespace twinslam::gnss
