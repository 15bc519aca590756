#pragma once
// GNSS fix errors by height above ground: urban GNSS is worst near the ground (blocked and reflected signals) and
// improves with height. What `twinslam gnss errors DIR` prints for a simulated or recorded flight.
#include <string>
#include <vector>

namespace twinslam::gnss {

struct HeightSample {
  double height_m = 0;      // true antenna height above ground [m]
  double horizontal_m = 0;  // horizontal error of the fix [m]
  double vertical_m = 0;    // |vertical error| [m]
};

struct BandStats {
  std::string name;         // "0-5", ..., "> 20"
  double low_m = 0, high_m = 0;  // [low, high) [m]; high = +inf for the last band
  std::size_t fixes = 0;
  double h_median_m = 0, h_mean_m = 0, h_p95_m = 0, v_median_m = 0;
};

// Bands [edges[0], edges[1]), ..., [edges.back(), inf); samples below edges[0] are counted in the first band.
// Default edges: 0, 5, 10, 20 m (issue 13).
std::vector<BandStats> errors_by_height(const std::vector<HeightSample>& samples,
                                        const std::vector<double>& edges = {0, 5, 10, 20});

}  // namespace twinslam::gnss
