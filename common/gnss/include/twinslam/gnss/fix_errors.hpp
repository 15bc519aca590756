#pragma once
// Errors of receiver fixes against ground truth, split in the local horizontal plane and the vertical (ENU at the
// true position), and their statistics: what `twinslam gnss solve` prints.
#include <vector>

#include "twinslam/gnss/receiver.hpp"
#include "twinslam/gnss/smartloc.hpp"

namespace twinslam::gnss {

struct FixError {
  double t_s = 0;
  double horizontal_m = 0;  // |(east, north)| of fix - truth [m]
  double vertical_m = 0;    // |up| [m]
};

// For each valid fix, the truth point with the nearest time within max_gap_s (fixes without one are skipped).
std::vector<FixError> fix_errors(const std::vector<Fix>& fixes, const std::vector<TruthPoint>& truth,
                                 double max_gap_s = 0.05);

struct FixErrorStats {
  std::size_t epochs = 0;   // epochs given to the receiver
  std::size_t fixes = 0;    // of them with a valid fix and a truth point
  double h_err_median_m = 0, h_err_p95_m = 0, h_err_rmse_m = 0, v_err_median_m = 0;
};

FixErrorStats fix_error_stats(std::size_t epochs, const std::vector<FixError>& errors);

}  // namespace twinslam::gnss
