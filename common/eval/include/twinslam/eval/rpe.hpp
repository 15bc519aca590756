#pragma once
// Relative pose error over sub-trajectories of fixed travelled length (Zhang & Scaramuzza, IROS 2018, Sec. IV-B; the
// KITTI odometry metric): for every start pose i, the pose j whose ground-truth distance along the path from i is
// closest to L (within 20 % of L) closes a segment; the error is E = (T_gt_i^-1 T_gt_j)^-1 (T_est_i^-1 T_est_j).
// Translation error |t_E| is reported in % of the segment's ground-truth path length, rotation angle(R_E) in deg/m.
// Both are invariant to the alignment (|t_E| and angle(R_E) do not change under the rpg toolbox's re-expression of E
// in the world orientation), except for the scale of a sim3 alignment.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/eval/stats.hpp"

namespace twinslam::eval {

struct RpeSegment {
  std::string key;                    // "50m" for fixed lengths, "20%" for fractions of the trajectory length
  double length_m = 0.0;              // nominal segment length L [m]
  std::vector<double> trans_pct;      // per segment: 100 |t_E| / path length
  std::vector<double> rot_deg_per_m;  // per segment: angle(R_E) / path length
  ErrorStats trans_pct_stats, rot_deg_per_m_stats;
};

// Largest accepted |actual - L| / L for a segment.
constexpr double kRpeLengthTolerance = 0.2;

// One RpeSegment per (key, L) entry, in order; a length longer than the trajectory gives n = 0.
std::vector<RpeSegment> compute_rpe(const std::vector<Eigen::Isometry3d>& T_WB_gt,
                                    const std::vector<Eigen::Isometry3d>& T_WB_est,
                                    const std::vector<std::pair<std::string, double>>& lengths_m);

// Cumulative path length at each pose [m], starting at 0.
std::vector<double> cumulative_distance(const std::vector<Eigen::Isometry3d>& T_WB);

}  // namespace twinslam::eval
