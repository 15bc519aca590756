#include "twinslam/gnss/height_bands.hpp"

#include <cmath>
#include <limits>

#include "twinslam/eval/stats.hpp"

namespace twinslam::gnss {
namespace {

std::string band_name(double low, double high) {
  const auto text = [](double v) { return std::to_string(static_cast<long>(std::lround(v))); };
  return std::isinf(high) ? "> " + text(low) : text(low) + "-" + text(high);
}

}  // namespace

std::vector<BandStats> errors_by_height(const std::vector<HeightSample>& samples, const std::vector<double>& edges) {
  std::vector<BandStats> out;
  for (std::size_t b = 0; b < edges.size(); ++b) {
    BandStats s;
    s.low_m = edges[b];
    s.high_m = b + 1 < edges.size() ? edges[b + 1] : std::numeric_limits<double>::infinity();
    s.name = band_name(s.low_m, s.high_m);
    std::vector<double> h, v;
    for (const HeightSample& x : samples) {
      const bool in = (b == 0 || x.height_m >= s.low_m) && x.height_m < s.high_m;
      if (!in) continue;
      h.push_back(x.horizontal_m);
      v.push_back(x.vertical_m);
    }
    s.fixes = h.size();
    s.h_median_m = eval::quantile(h, 0.5);
    s.h_mean_m = eval::compute_stats(h).mean;
    s.h_p95_m = eval::quantile(h, 0.95);
    s.v_median_m = eval::quantile(v, 0.5);
    out.push_back(s);
  }
  return out;
}

}  // namespace twinslam::gnss
