#pragma once
// Loosely coupled GNSS + VIO fusion (issue 13, mode `vio-gnss-loose`; the paper's VINS-Fusion row of Table I). The
// VIO runs untouched in its own frame L; a separate pose graph in W takes its poses as relative constraints and the
// GNSS fixes as absolute ones (VINS-Fusion's global_fusion node, Qin et al. 2019), and answers T_WL: the transform that
// carries the newest VIO pose to its fused pose in W. Unlike the tightly coupled window terms (gnss_provider.hpp),
// nothing flows back into the VIO: a GNSS error bends the global path, never the velocity or the biases.
//
// Done better than VINS-Fusion's node, point by point:
//  - the graph has one node per `node_interval_s` of VIO time, not one per VIO pose, and each fix reaches its node
//    through the VIO motion between them, so no fix is dropped or paired with a pose up to a frame away;
//  - the odometry constraints get sigmas that grow with the distance travelled between nodes (VIO drift is per metre),
//    not one fixed weight whatever the distance;
//  - time-correlated urban GNSS errors come in with inflated covariances (the caller's fusion.gnss_correlation_s, as
//    for the window terms), and a Huber loss bounds NLOS outliers;
//  - a sliding window of `window_nodes` nodes keeps the cost constant over a long flight (VINS-Fusion re-solves the
//    whole history at every fix); the oldest node keeps a prior at its last estimate for what the dropped ones said.
// 6-vectors here are (translation, rotation), whitened; graph poses are T_WB of the nodes.
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::estimator {

struct LooseGnssFusionConfig {
  double node_interval_s = 1.0;          // VIO time between graph nodes [s]
  int window_nodes = 120;                // nodes optimized together; older ones leave the graph [1]
  double odometry_sigma_per_m = 0.02;    // VIO relative translation sigma per metre travelled between nodes [1]
  double odometry_min_sigma_m = 0.02;    // ... at least [m]
  double odometry_deg_per_m = 0.05;      // VIO relative rotation sigma per metre travelled [deg/m]
  double odometry_min_sigma_deg = 0.05;  // ... at least [deg]
  double prior_sigma_m = 1.0;            // prior on the oldest node of the window, at its last estimate [m]
  double prior_sigma_deg = 1.0;          // [deg]
  double huber_delta = 3.0;              // robust loss on the whitened 3-residual of a fix [1]
  double max_pairing_dt_s = 0.2;         // a fix needs VIO poses within this of its stamp [s]
  int max_iterations = 10;               // Ceres iterations per solve [1]
  Eigen::Vector3d lever_arm_B = Eigen::Vector3d::Zero();  // GNSS antenna in the body frame [m]
  void validate() const;                 // throws twinslam::InputError naming the field
};

struct LooseGnssFusionCounts {
  unsigned long long fixes_in = 0, fixes_used = 0, fixes_unpaired = 0, solves = 0, nodes = 0;
};

class LooseGnssFusion {
 public:
  explicit LooseGnssFusion(const LooseGnssFusionConfig& config = {});

  // Forgets the graph until the next start() (the VIO was reset: its frame L is a new one).
  void stop() { started_ = false; }
  // The graph starts once the world alignment is known (the GNSS fit of world_aligner.hpp): T_WL places the VIO
  // frame in W. Nodes and fixes before this are not kept. Calling it again restarts the graph (after a VIO reset).
  void start(const Eigen::Isometry3d& T_WL);
  bool started() const { return started_; }
  // A VIO pose (increasing stamps; an older or equal stamp is ignored).
  void add_odometry(std::int64_t stamp_ns, const Eigen::Isometry3d& T_LB);
  // A GNSS fix p_W with covariance cov_W (ENU; already inflated for time correlation) [m, m^2]. Used once VIO poses
  // bracket its stamp; an unusable one (NaN, not positive definite) or one no VIO pose comes near is counted unpaired.
  void add_fix(std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const Eigen::Matrix3d& cov_W);
  // The newest fused alignment: T_WB = T_WL() * T_LB for the newest VIO pose.
  Eigen::Isometry3d T_WL() const { return T_WL_; }
  const LooseGnssFusionCounts& counts() const { return counts_; }

  struct Fix {
    Eigen::Vector3d z_W;
    Eigen::Matrix3d cov_W;                // as given (inflated for correlation by the caller)
    Eigen::Isometry3d T_node_fix;         // VIO motion from the node to the fix's stamp: T_{B_node B_fix}
  };
  struct Node {
    std::int64_t stamp_ns = 0;
    Eigen::Isometry3d T_LB;               // VIO pose (constant)
    Eigen::Isometry3d T_WB;               // graph estimate
    std::vector<Fix> fixes;
  };

 private:
  void pair_pending();
  void attach(std::int64_t stamp_ns, const Eigen::Isometry3d& T_LB_fix, const Eigen::Vector3d& z_W,
              const Eigen::Matrix3d& cov_W);
  void solve();

  LooseGnssFusionConfig config_;
  bool started_ = false;
  Eigen::Isometry3d T_WL_ = Eigen::Isometry3d::Identity();
  std::deque<Node> nodes_;
  std::optional<Eigen::Isometry3d> prior_T_WB_;  // on nodes_.front()
  struct Pose {
    std::int64_t stamp_ns;
    Eigen::Isometry3d T_LB;
  };
  std::optional<Pose> previous_, newest_;         // the last two VIO poses
  struct Pending {
    std::int64_t stamp_ns;
    Eigen::Vector3d z_W;
    Eigen::Matrix3d cov_W;
  };
  std::vector<Pending> pending_;                  // fixes newer than the newest VIO pose
  LooseGnssFusionCounts counts_;
};

// The graph's solve, for tests: optimizes nodes' T_WB (the front one held by `prior_T_WB` if given).
void solve_loose_graph(std::deque<LooseGnssFusion::Node>& nodes, const std::optional<Eigen::Isometry3d>& prior_T_WB,
                       const LooseGnssFusionConfig& config);

}  // namespace twinslam::estimator
