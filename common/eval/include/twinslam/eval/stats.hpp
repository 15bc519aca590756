#pragma once
// Summary statistics of a list of errors, the set rpg_trajectory_evaluation and evo report.
#include <vector>

namespace twinslam::eval {

struct ErrorStats {
  std::size_t n = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, std = 0.0, min = 0.0, max = 0.0;  // std: population (1/n)
};

// All zero with n = 0 for an empty list.
ErrorStats compute_stats(const std::vector<double>& values);

// Linear-interpolated quantile q in [0, 1] of an unsorted list (box plots); 0 for an empty list.
double quantile(std::vector<double> values, double q);

}  // namespace twinslam::eval
