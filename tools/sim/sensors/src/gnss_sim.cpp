#include "twinslam/sim/gnss_sim.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <GeographicLib/LocalCartesian.hpp>

#include "seeds.hpp"
#include "twinslam/sim/clock.hpp"

namespace twinslam::sim {

std::vector<GnssSample> simulate_gnss_at(const std::vector<std::int64_t>& stamps_ns,
                                         const std::vector<Eigen::Vector3d>& p_W, const GnssSimConfig& config,
                                         const Origin& origin, std::uint64_t seed) {
  std::mt19937_64 rng = detail::make_rng(seed, detail::Stream::Gnss);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> satellites(8, 12);
  const GeographicLib::LocalCartesian enu(origin.lat_deg, origin.lon_deg, origin.alt_m);
  const Eigen::Vector3d sigma(config.sigma_m, config.sigma_m, 1.5 * config.sigma_m);  // stated std [m, ENU]
  const Eigen::Vector3d sigma_bias = 0.6 * sigma, sigma_white = 0.8 * sigma;

  std::vector<GnssSample> out;
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  int sats = satellites(rng);
  for (std::size_t i = 0; i < stamps_ns.size(); ++i) {
    Eigen::Vector3d n_bias, n_white;
    for (int k = 0; k < 3; ++k) n_bias[k] = normal(rng);
    for (int k = 0; k < 3; ++k) n_white[k] = normal(rng);
    if (i == 0) {
      bias = sigma_bias.cwiseProduct(n_bias);  // stationary start
    } else {
      // First-order Gauss-Markov, exact discretization: b_k = phi b_{k-1} + sqrt(1 - phi^2) sigma_b n.
      const double phi = std::exp(-(time_s(stamps_ns[i]) - time_s(stamps_ns[i - 1])) / kGnssBiasTau);
      bias = phi * bias + std::sqrt(1 - phi * phi) * sigma_bias.cwiseProduct(n_bias);
    }
    if (i % 50 == 0 && i > 0) sats = std::clamp(sats + static_cast<int>(rng() % 3) - 1, 8, 12);  // slow change
    const Eigen::Vector3d measured = p_W[i] + bias + sigma_white.cwiseProduct(n_white);
    GnssSample g;
    g.stamp_ns = stamps_ns[i];
    enu.Reverse(measured.x(), measured.y(), measured.z(), g.latitude_deg, g.longitude_deg, g.altitude_m);
    g.std_east_m = sigma.x();
    g.std_north_m = sigma.y();
    g.std_up_m = sigma.z();
    g.num_satellites = sats;
    g.true_p_W = p_W[i];
    g.bias_W = bias;
    out.push_back(g);
  }
  return out;
}

std::vector<GnssSample> simulate_gnss(const FlightTrajectory& trajectory, const GnssSimConfig& config,
                                      const Origin& origin, std::uint64_t seed) {
  const std::vector<std::int64_t> stamps = sample_stamps(config.rate_hz, trajectory.duration());
  std::vector<Eigen::Vector3d> p_W;
  p_W.reserve(stamps.size());
  for (const auto s : stamps) p_W.push_back(trajectory.at(time_s(s)).p_W);
  return simulate_gnss_at(stamps, p_W, config, origin, seed);
}

Eigen::Vector3d gnss_to_enu(const GnssSample& sample, const Origin& origin) {
  const GeographicLib::LocalCartesian enu(origin.lat_deg, origin.lon_deg, origin.alt_m);
  Eigen::Vector3d p;
  enu.Forward(sample.latitude_deg, sample.longitude_deg, sample.altitude_m, p.x(), p.y(), p.z());
  return p;
}

}  // namespace twinslam::sim
