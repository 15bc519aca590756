#pragma once
// What the estimator does with global inputs (paper Sec. III-C/D), free of DDS: the node converts messages and calls
// this in sensor-time order (sensor_worker.hpp).
//  - GNSS fixes (in W) pair with the estimated positions to find the initial alignment T_WL (eq. 11, WorldAligner).
//    A fit whose heading sigma is below provisional_yaw_sigma_deg starts the window's T_WL provisionally, with the
//    fit's sigmas: registration then searches the heading within them and its results refine T_WL (the paper uses
//    registered positions in place of GNSS once registration succeeds, Sec. III-D). The alignment is *declared*
//    (Odometry in W) when the heading sigma of T_WL is below aligner.converged_yaw_sigma_deg - of the GNSS fit, or of
//    the window's own estimate once registrations have acted on it (Boche et al. 2022's convergence test). After a
//    long registration outage (drift grows) the alignment is found again from recent fixes (paper Sec. V) - applied
//    only when that fit is more certain than the estimate it would replace.
//  - Without GNSS, an initial pose given by the user ("E N U YAW", the paper's "set manually") starts it, declared
//    at once if its heading sigma passes the same test, else when registrations have made it pass.
//  - Accepted map registrations become MapRegistration terms (map_registration_provider.hpp) on their keyframe,
//    read against the keyframe pose and T_WL that were published with the LocalMap they answer.
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "twinslam/estimator/gnss_jump.hpp"
#include "twinslam/estimator/gnss_provider.hpp"
#include "twinslam/estimator/loose_gnss_fusion.hpp"
#include "twinslam/estimator/map_registration_provider.hpp"
#include "twinslam/estimator/registration_gate.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"
#include "twinslam/estimator/world_aligner.hpp"

namespace twinslam::estimator {

struct GlobalFusionConfig {
  bool fuse_registrations = false;      // twin modes
  bool align_from_gnss = false;         // use GNSS fixes for the initial alignment (and re-alignment)
  bool fuse_gnss = false;               // GNSS fixes as window terms once T_WL is set (vio-gnss, vio-twin-gnss)
  // GNSS fixes in a pose graph apart from the window (vio-gnss-loose): the output T_WL is the graph's, the VIO is
  // untouched. Starts when the alignment is declared (needs align_from_gnss); not with fuse_gnss.
  bool fuse_gnss_loose = false;
  // Re-align from GNSS when no registration was accepted for this long after alignment (0: never) [s].
  double realign_after_s = 30.0;
  // A registration re-admitted by registration's persistence gate (Registration.readmitted: the estimator's covariance
  // called it implausible, yet keyframes a landmark horizon apart kept finding it) re-opens the alignment: T_WL is
  // set where that registration puts the keyframe, its prior sigmas are the correction's size, and the registrations
  // fused before it (which agreed with the estimate now found wrong) leave the window. Measured on city-loops
  // (realistic sensors, ideal tracks): a 3.8 deg heading declared at 25 s stayed for the whole flight although ICP
  // found the right one from 43 s on; ICP's near-zero corrections around the wrong estimate kept being accepted.
  bool realign_on_readmitted_registration = true;
  // ... but only when the correction is larger than one registration resolves (bench_registration_floor: up to
  // 0.5 m), in position at the keyframe or in heading; a smaller one is fused as any other. Re-opening on a 0.1 m
  // correction (tracked images on city-loops, at 187 s) dropped the registrations that held the estimate, which then
  // drifted 1-3 m (ATE 1.40 m, 0.57 m without re-opening).
  double realign_min_correction_m = 1.0;    // [m]
  double realign_min_correction_deg = 1.0;  // [deg]
  // A heading sigma below the threshold does not make a position right: the window's covariance of T_WL can shrink
  // under registrations while the estimate is still metres from where they put it. The alignment is declared from
  // registrations (check_declaration) only when the last declare_agreeing_registrations ones registration accepted
  // (fused, or refused by the estimator's own gate) each moved their keyframe by at most declare_max_correction_m:
  // the estimate already sits where the twin says. Measured on city-survey (ideal tracks): declared on the heading
  // alone at 19 s while the next corrections were 7.8, 3.5 and 1.5 m; with 3 agreeing, at 80 s.
  int declare_agreeing_registrations = 3;  // [1]; 0: the heading sigma alone declares
  double declare_max_correction_m = 1.0;   // [m]
  double initial_pose_position_sigma_m = 5.0;  // prior of a user-given initial pose [m]
  double initial_pose_yaw_sigma_deg = 5.0;     // [deg]
  double gnss_alignment_sigma_scale = 1.0;     // the T_WL prior's sigmas = the aligner's sigmas times this [1]
  // Urban GNSS errors (NLOS, multipath, atmosphere) persist for seconds: fixes closer than this are not independent.
  // Each fix's covariance is multiplied by max(1, gnss_correlation_s / interval since the previous fix), so the fit's
  // sigmas count one independent fix per correlation time (0: fixes taken as independent) [s]. Measured on city-loops
  // with ray-traced GNSS (ideal tracks): 0 s -> vio-twin 8.93 m (an early fit biased by NLOS near the tower, declared
  // 10 m / 17 deg off), 30 s -> 0.385 m.
  double gnss_correlation_s = 30.0;
  // A GNSS fit with a heading sigma below this starts T_WL provisionally (for registration to refine; Odometry stays
  // in L until declared) [deg]; 0: only a converged fit (aligner.converged_yaw_sigma_deg) starts it
  double provisional_yaw_sigma_deg = 30.0;
  WorldAlignerConfig aligner;
  RegistrationGateConfig registration_gate;  // the estimator's own check of each registration (registration_gate.hpp)
  GnssJumpConfig gnss_jump;                  // fixes after a jump are refused (gnss_jump.hpp)
  MapRegistrationProviderConfig registration;
  GnssProviderConfig gnss;
  LooseGnssFusionConfig loose;
  void validate() const;  // throws twinslam::InputError naming the field
};

// An initial pose of body B in W: position E, N, U [m] and yaw [deg] (heading of B's x axis from East, CCW).
struct InitialPose {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;
  // The pose's own prior sigmas (a resumed checkpoint, resume.hpp); without them the config's initial_pose_* ones.
  std::optional<WorldAlignmentSigmas> sigmas;
};

struct GlobalFusionCounts {
  unsigned long long gnss_in = 0, gnss_paired = 0, alignments = 0, registrations_in = 0, registrations_accepted = 0,
                     registrations_unknown_keyframe = 0, registrations_before_alignment = 0,
                     realignments_declined = 0,  // after an outage, the GNSS fit was less certain than the estimate
                     provisional_alignments = 0,  // T_WL set (or replaced) from a fit not yet converged
                     registration_realignments = 0,  // T_WL re-opened by a re-admitted registration
                     registrations_invalid = 0,  // accepted by registration but not fusable (registration_problem)
                     registrations_refused = 0;  // accepted by registration, refused by registration_gate.hpp
};

class GlobalFusion {
 public:
  GlobalFusion(SlidingWindowEstimator& estimator, const GlobalFusionConfig& config,
               std::optional<InitialPose> initial_pose = std::nullopt);
  // T_WL from this pose of the body at the first tracking frame from now on, as the constructor's initial_pose (a
  // restarted estimator resuming from its checkpoint); ignored once aligned.
  void start_from(const InitialPose& pose) { initial_pose_ = pose; }

  // A GNSS fix at `stamp_ns`: p_W with covariance (ENU) [m, m^2]. A fix after a jump is refused (gnss_jump.hpp,
  // counted in gnss_jump_counts()) and used for nothing.
  void on_gnss(std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const Eigen::Matrix3d& cov_W);
  // A registration answering the keyframe at `keyframe_stamp_ns` (only accepted ones are fused). correction_W: dT of
  // eq. (3) as a transform of W; information: 6x6 (rotation, translation) about the keyframe position.
  // readmitted: Registration.readmitted (see realign_on_readmitted_registration). Returns why an accepted one is not
  // fused: not fusable (registration_problem, counted as registrations_invalid) or refused by the estimator's own
  // gate (registration_gate.hpp, counted as registrations_refused); "" otherwise.
  std::string on_registration(std::int64_t keyframe_stamp_ns, bool accepted, const Eigen::Isometry3d& correction_W,
                       const Eigen::Matrix<double, 6, 6>& information, bool readmitted = false);
  // After each frame: remembers the estimate (GNSS pairing) and, for a keyframe, its published LocalMap pose.
  void after_frame(const FrameEstimate& estimate, const std::optional<LocalMapEstimate>& local_map);

  const GlobalFusionCounts& counts() const { return counts_; }
  const MapRegistrationCounts& registration_counts() const { return provider_->counts(); }
  const GnssProviderCounts& gnss_counts() const { return gnss_provider_->counts(); }
  const GnssJumpCounts& gnss_jump_counts() const { return gnss_jump_.counts(); }
  const LooseGnssFusionCounts& loose_counts() const { return loose_.counts(); }
  // The alignment to publish with the newest frame when it is not the window's: the loose graph's (fuse_gnss_loose,
  // once started); nothing otherwise.
  std::optional<Eigen::Isometry3d> output_T_WL() const;
  std::optional<WorldAlignment4Dof> last_alignment() const { return last_alignment_; }
  // The keyframe covariance published with the LocalMap of `keyframe_stamp_ns` (LocalMap.T_WB_covariance, in
  // registration's order (dtheta_W, dp_W)): computed when a keyframe is published while T_WL is estimated in a
  // twin mode; what the registration gates of both services test a correction against.
  std::optional<Eigen::Matrix<double, 6, 6>> published_covariance(std::int64_t keyframe_stamp_ns) const;
  // T_WL is set and its heading is certain enough to call T_WB a pose in W (Odometry ODOM_ALIGNED).
  bool world_declared() const { return aligned_ && declared_; }

 private:
  void try_align(std::int64_t stamp_ns);
  // Sets T_WL from a GNSS fit (declared if converged) and notes when.
  void set_from_fit(const WorldAlignment4Dof& fit, std::int64_t stamp_ns, bool declared);
  // Provisional alignment refined by registrations: declared once the window's own heading sigma passes the test.
  void check_declaration();
  // A re-admitted registration (correction_W of the keyframe published at T_WL, T_LB): T_WL set where it puts the
  // keyframe, with the correction's size as prior sigmas; the registrations fused so far leave the window.
  void reopen_alignment(const Eigen::Isometry3d& correction_W, const Eigen::Isometry3d& T_WL,
                        const Eigen::Isometry3d& T_LB);
  // The correction moves the keyframe T_WB by more than realign_min_correction_m or turns it by more than
  // realign_min_correction_deg in heading.
  bool reopening_warranted(const Eigen::Isometry3d& correction_W, const Eigen::Isometry3d& T_WB) const;
  // The last declare_agreeing_registrations corrections registration accepted each moved their keyframe by at most
  // declare_max_correction_m (always true when declare_agreeing_registrations is 0).
  bool registrations_agree() const;
  // After an outage: whether the fit (sigmas of the T_WL prior it would set) is more certain, in heading and in
  // horizontal position, than the estimator's own newest pose in W.
  bool realignment_helps(const WorldAlignmentSigmas& fit) const;

  SlidingWindowEstimator& estimator_;
  GlobalFusionConfig config_;
  std::optional<InitialPose> initial_pose_;
  std::shared_ptr<MapRegistrationProvider> provider_;
  std::shared_ptr<GnssProvider> gnss_provider_;
  WorldAligner aligner_;
  GnssJumpDetector gnss_jump_;
  LooseGnssFusion loose_;
  std::optional<WorldAlignment4Dof> last_alignment_;
  std::optional<FrameEstimate> last_frame_;
  std::int64_t last_gnss_ns_ = -1;  // stamp of the previous fix (gnss_correlation_s)
  struct Published {
    Eigen::Isometry3d T_LB, T_WL;
    std::optional<Eigen::Matrix<double, 6, 6>> covariance;  // published_covariance()
  };
  std::map<std::int64_t, Published> published_;  // by keyframe stamp
  std::int64_t last_accepted_ns_ = -1;  // last accepted registration (or alignment) [sensor time]
  bool aligned_ = false;   // T_WL is set (provisionally or declared)
  bool declared_ = false;  // ... and certain enough to output poses in W
  double provisional_yaw_sigma_deg_ = 0.0;      // heading sigma of the provisional T_WL prior [deg]
  unsigned long long accepted_at_provisional_ = 0;  // registrations_accepted when T_WL was last set provisionally
  std::deque<double> recent_corrections_m_;  // how far the newest registrations (fused or refused) move their keyframe [m]
  GlobalFusionCounts counts_;
};

}  // namespace twinslam::estimator
