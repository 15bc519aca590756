#include "twinslam/eval/stats.hpp"

#include <algorithm>
#include <cmath>

namespace twinslam::eval {

ErrorStats compute_stats(const std::vector<double>& values) {
  ErrorStats s;
  s.n = values.size();
  if (values.empty()) return s;
  double sum = 0.0, sum_sq = 0.0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  double dev_sq = 0.0;  // second pass: sum_sq/n - mean^2 cancels badly for errors with a large common offset
  for (double v : values) dev_sq += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(dev_sq / n);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  s.min = *lo;
  s.max = *hi;
  s.median = quantile(values, 0.5);
  return s;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(pos));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double frac = pos - static_cast<double>(below);
  return values[below] + frac * (values[above] - values[below]);
}

}  // namespace twinslam::eval
