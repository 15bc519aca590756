#pragma once
// The degenerate stretch of a streets flight: a straight run of several blocks along one street whose one side is
// lined with facades taller than the drone, flown closer to that side, so that one wall dominates the view (the case
// where registration to the twin is constrained in one direction only). Private to the library.
#include <vector>

#include <Eigen/Core>

#include "street_graph.hpp"

namespace twinslam::sim::detail {

inline constexpr int kFacadeBlocks = 3;            // segments of the stretch: 180 m of street on the default grid
inline constexpr double kFacadeDistance_m = 6.0;   // flight line to the nearest facade of the row [m]
inline constexpr double kFacadeReach_m = 10.0;     // a facade within this of the centreline lines the street [m]
inline constexpr double kFacadeRise_m = 5.0;       // a facade counts when its eave is this far above the drone [m]
inline constexpr double kRoofClearance_m = 4.0;    // buildings whose top comes this close below the drone or higher
                                                   // keep kFacadeDistance_m sideways [m]

struct FacadeStretch {
  std::vector<GridNode> nodes;                      // kFacadeBlocks + 1 collinear intersections
  Eigen::Vector2d side_W = Eigen::Vector2d::Zero(); // unit vector from the centreline toward the facade row [W]
  double shift_m = 0;                               // flight line's offset from the centreline along side_W [m]
  double coverage = 0;                              // fraction of the stretch lined by tall facades on that side
  double opposite_coverage = 0;                     // the same for any facade on the other side
};

// Fraction of the centreline a -> b (inside the intersections, where the flight is straight) that has a facade of a
// building with eave >= min_eave_m within kFacadeReach_m on `side_W`; `nearest_m` gets the smallest distance from
// the centreline to any footprint on that side reaching min_top_m or higher [m] (infinity if none).
double facade_coverage(const Eigen::Vector2d& a_W, const Eigen::Vector2d& b_W, const Eigen::Vector2d& side_W,
                       const std::vector<BuildingHint>& buildings, double min_eave_m, double min_top_m,
                       double street_width_m, double* nearest_m);

// Every straight run of kFacadeBlocks segments and side, best first (most tall facades on that side; then fewest
// facades on the other; then grid order), for a flight at altitude z_m. Empty if the grid has no such run.
std::vector<FacadeStretch> rank_facade_stretches(const StreetGraph& graph, const std::vector<BuildingHint>& buildings,
                                                 double z_m);

}  // namespace twinslam::sim::detail
