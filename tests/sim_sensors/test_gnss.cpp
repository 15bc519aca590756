// GNSS: fixes converted back to ENU match the truth within the stated noise; the bias is slow (Gauss-Markov).
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/gnss_sim.hpp"

namespace twinslam::sim {
namespace {

// Two hours at 5 Hz along a slow circle: many bias correlation times (tau = 60 s), so the RMS is well determined.
std::vector<GnssSample> long_run(const GnssSimConfig& cfg, const Origin& origin, std::uint64_t seed) {
  const std::vector<std::int64_t> stamps = sample_stamps(cfg.rate_hz, 7200);
  std::vector<Eigen::Vector3d> p_W;
  for (const auto s : stamps) {
    const double t = time_s(s);
    p_W.emplace_back(200 * std::cos(t / 300), 150 * std::sin(t / 300), 20 + 5 * std::sin(t / 100));
  }
  return simulate_gnss_at(stamps, p_W, cfg, origin, seed);
}

TEST(SimGnss, BackToEnuMatchesTruthWithinStatedNoise) {
  GnssSimConfig cfg;
  cfg.sigma_m = 1.2;
  const Origin origin;
  const auto fixes = long_run(cfg, origin, 5);
  Eigen::Array3d sq = Eigen::Array3d::Zero(), sigma_sq = Eigen::Array3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& g : fixes) {
    const Eigen::Vector3d e = gnss_to_enu(g, origin) - g.true_p_W;
    sq += e.array().square();
    mean += e;
    sigma_sq += Eigen::Array3d(g.std_east_m, g.std_north_m, g.std_up_m).square();
    EXPECT_GE(g.num_satellites, 8);
    EXPECT_LE(g.num_satellites, 12);
  }
  const double n = static_cast<double>(fixes.size());
  const Eigen::Array3d ratio = (sq / n).sqrt() / (sigma_sq / n).sqrt();  // RMS / stated sigma, per axis
  std::printf("RMS/sigma east %.3f north %.3f up %.3f\n", ratio[0], ratio[1], ratio[2]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(ratio[i], 1.0, 0.2) << "axis " << i;
  EXPECT_LT((mean / n).norm(), 0.3 * cfg.sigma_m);  // no systematic offset over many tau
  EXPECT_DOUBLE_EQ(fixes[0].std_up_m, 1.5 * cfg.sigma_m);
}

TEST(SimGnss, BiasIsSlowAndWhiteNoiseIsFast) {
  GnssSimConfig cfg;
  const Origin origin;
  const auto fixes = long_run(cfg, origin, 9);
  // Lag-1 (0.2 s) correlation of the bias is exp(-0.2/60) ~ 1; the total error decorrelates much faster.
  double bb = 0, b0 = 0, ee = 0, e0 = 0;
  for (std::size_t i = 1; i < fixes.size(); ++i) {
    bb += fixes[i].bias_W.x() * fixes[i - 1].bias_W.x();
    b0 += fixes[i].bias_W.x() * fixes[i].bias_W.x();
    const double e = gnss_to_enu(fixes[i], origin).x() - fixes[i].true_p_W.x();
    const double ep = gnss_to_enu(fixes[i - 1], origin).x() - fixes[i - 1].true_p_W.x();
    ee += e * ep;
    e0 += e * e;
  }
  EXPECT_GT(bb / b0, 0.99);
  EXPECT_NEAR(ee / e0, 0.36, 0.08);  // bias share of the variance: 0.6^2
  const Eigen::Vector3d enu = gnss_to_enu(fixes[0], origin) - fixes[0].true_p_W;
  EXPECT_LT(enu.norm(), 6 * 1.5 * cfg.sigma_m);
}

TEST(SimGnss, FollowsTheFlightAtItsRateAndIsReproducible) {
  const Scenario sc = builtin_scenario("tiny");
  const FlightTrajectory f = make_flight_trajectory(sc, testing::hints_for(sc));
  const auto a = simulate_gnss(f, sc.gnss, sc.origin, sc.seed), b = simulate_gnss(f, sc.gnss, sc.origin, sc.seed);
  ASSERT_EQ(a.size(), static_cast<std::size_t>(sc.trajectory.duration_s * sc.gnss.rate_hz + 1));
  EXPECT_EQ(a[1].stamp_ns - a[0].stamp_ns, 200'000'000);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].latitude_deg, b[i].latitude_deg);
    EXPECT_LT((a[i].true_p_W - f.at(time_s(a[i].stamp_ns)).p_W).norm(), 1e-12);
  }
  // Near the origin, latitude grows northward by about 1 deg per 111 km.
  EXPECT_NEAR(a[0].latitude_deg, sc.origin.lat_deg + gnss_to_enu(a[0], sc.origin).y() / 111'195.0, 1e-5);
}

}  // namespace
}  // namespace twinslam::sim
