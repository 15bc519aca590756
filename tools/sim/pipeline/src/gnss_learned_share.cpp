// The learned GNSS model's choice of received satellites (the share per height and elevation, the inclusion
// probabilities given the GP's count, Pareto order sampling) and its error coordinate (gnss_learned.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "twinslam/sim/gnss_learned.hpp"

namespace twinslam::sim {
namespace {

std::size_t elevation_bin(double elevation_deg, double mask_deg, std::size_t bins) {
  const double b = std::max(0.0, (elevation_deg - mask_deg) / kElevationBinDeg);
  return std::min(bins - 1, static_cast<std::size_t>(b));
}

std::size_t height_bin(double height_m, std::size_t bins) {
  return std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, height_m / kShareHeightBinM)));
}

}  // namespace

double error_to_log(double error_m) { return std::copysign(std::log1p(std::abs(error_m)), error_m); }
double error_from_log(double log_error) { return std::copysign(std::expm1(std::abs(log_error)), log_error); }

std::vector<double> inclusion_probabilities(const std::vector<double>& shares, std::size_t n) {
  std::vector<double> pi(shares.size(), 0.0);
  std::vector<bool> sure(shares.size(), false);
  // Scale the shares to sum to n; any that would pass 1 is taken for sure and the rest rescaled (at most one round
  // per satellite).
  for (std::size_t round = 0; round <= shares.size(); ++round) {
    double free_sum = 0, taken = 0;
    for (std::size_t j = 0; j < shares.size(); ++j) sure[j] ? taken += 1 : free_sum += std::max(shares[j], 1e-9);
    const double scale = free_sum > 0 ? std::max(0.0, static_cast<double>(n) - taken) / free_sum : 0;
    bool capped = false;
    for (std::size_t j = 0; j < shares.size(); ++j) {
      if (sure[j]) continue;
      pi[j] = scale * std::max(shares[j], 1e-9);
      if (pi[j] >= 1) pi[j] = 1, sure[j] = true, capped = true;
    }
    if (!capped) break;
  }
  return pi;
}

double pareto_rank(double u, double pi) {
  if (pi >= 1) return 0;
  if (pi <= 0) return std::numeric_limits<double>::infinity();
  return u * (1 - pi) / ((1 - u) * pi);
}

std::vector<std::vector<double>> received_share_table(const GnssTrainingData& data) {
  const double mask = data.elevation_mask_deg;
  const std::size_t el_bins = static_cast<std::size_t>(std::ceil((90 - mask) / kElevationBinDeg - 1e-9));
  const double top = data.heights_m.empty() ? 0 : *std::max_element(data.heights_m.begin(), data.heights_m.end());
  const std::size_t h_bins = static_cast<std::size_t>(top / kShareHeightBinM) + 1;
  std::vector<std::vector<double>> seen(h_bins, std::vector<double>(el_bins, 0.0)), got = seen;
  std::vector<double> seen_el(el_bins, 0.0), got_el(el_bins, 0.0);
  double seen_all = 0, got_all = 0;
  for (const TrainingSatellite& t : data.sky) {
    const std::size_t hb = height_bin(data.heights_m[t.position], h_bins), b = elevation_bin(t.elevation_deg, mask, el_bins);
    const double r = t.received ? 1 : 0;
    seen[hb][b] += 1, got[hb][b] += r, seen_el[b] += 1, got_el[b] += r, seen_all += 1, got_all += r;
  }
  const double overall = seen_all > 0 ? got_all / seen_all : 1.0;
  std::vector<std::vector<double>> share(h_bins, std::vector<double>(el_bins, 0.0));
  for (std::size_t b = 0; b < el_bins; ++b) {
    const double prior = (got_el[b] + kSharePriorSatellites * overall) / (seen_el[b] + kSharePriorSatellites);
    for (std::size_t hb = 0; hb < h_bins; ++hb) {
      share[hb][b] = (got[hb][b] + kSharePriorSatellites * prior) / (seen[hb][b] + kSharePriorSatellites);
    }
  }
  return share;
}


double received_share_at(const LearnedGnssModel& model, double height_m, double elevation_deg) {
  const auto& table = model.received_share;
  if (table.empty() || table[0].empty()) return 1.0;
  const std::size_t b = elevation_bin(elevation_deg, model.elevation_mask_deg, table[0].size());
  // Linear in height between the bins' centres, constant beyond the first and last.
  const double x = std::clamp(height_m / kShareHeightBinM - 0.5, 0.0, static_cast<double>(table.size() - 1));
  const std::size_t lo = static_cast<std::size_t>(x), hi = std::min(lo + 1, table.size() - 1);
  return table[lo][b] + (x - static_cast<double>(lo)) * (table[hi][b] - table[lo][b]);
}

}  // namespace twinslam::sim
