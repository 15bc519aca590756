#pragma once
// The registration library's one config struct (paper Sec. III-C): source-cloud preprocessing, point-to-plane ICP
// (eq. 2), the information weighting (eqs. 8-10 or the adaptive variant) and the acceptance tests.
// validate() is the one place the values are checked; parse_registration_config reads the YAML form (the commented
// default file is deploy/config/registration.yaml; every key there equals the default below).
#include <cstdint>
#include <string>

namespace twinslam::registration {

// A fault injected into the service's answers (issue 15: tests and demonstrations of what the estimator does with a
// wrong registration). registration.yaml:  faults: {correction_offset: {at_s: 23, duration_s: 3, east_m: 20}}
// Every registration accepted for a keyframe in [at_s, at_s + duration_s) seconds after the first LocalMap the service
// served for that vehicle goes out with its correction moved east_m metres east (its reason says so). Off while
// at_s < 0.
struct CorrectionFault {
  double at_s = -1.0;       // [s] after the vehicle's first LocalMap keyframe; < 0: off
  double duration_s = 0.0;  // [s]
  double east_m = 20.0;     // [m] added to the correction's translation along W's x (east)
  bool contains(std::int64_t keyframe_stamp_ns, std::int64_t first_stamp_ns) const;
  bool operator==(const CorrectionFault&) const = default;
};

// How the 6x6 information of an accepted registration is weighted (information.hpp).
enum class WeightMode {
  kPaper,     // eq. (10) as written: beta / trace(H) * exp(-gamma^2 / 2) * H
  kAdaptive,  // H / sigma^2 (robust, inflated residual variance), zero along poorly observed directions
  kFixed,     // a constant diagonal (ablation: geometry-blind weight)
};
const char* weight_mode_name(WeightMode mode);  // "paper", "adaptive", "fixed"

struct RegistrationConfig {
  // --- source cloud (preprocess.hpp) ---
  double min_quality = 0.5;     // landmarks with quality < this are dropped, quality in [0, 1]
  double voxel_size_m = 0.3;    // voxel downsampling edge [m]; 0 disables (one centroid per voxel)
  int outlier_neighbors = 8;    // statistical outlier removal: neighbours per point; 0 disables
  double outlier_stddev = 2.0;  // ... drop points whose mean neighbour distance > mean + this * stddev
  int min_points = 30;          // fewer source points after preprocessing: rejected (too few points)
  // The twin surface's own error along its normal [m]: each point-to-plane residual is weighted by
  // surface^2 / (surface^2 + the landmark's variance along the normal) (icp.hpp); 0 ignores the landmarks' covariances.
  // Off by default, by measurement: on city-loops / city-survey ATE_p was 0.316 / 0.289 m with 0, 0.317 / 0.425 with
  // 1.0, 0.350 / 0.523 with 0.5 and 0.470 / 0.557 with 0.2. The twin's error is per surface, so many poorly
  // triangulated far landmarks still average over more surfaces than a few good near ones.
  double surface_sigma_m = 0.0;

  // --- compute ---
  int threads = 1;  // threads for the nearest-neighbour searches (ICP association, outlier removal); results are
                    // identical for any count. 1: the pipeline's 2-core default, beside the estimator

  // --- ICP (icp.hpp), eq. (2) ---
  int max_iterations = 30;                  // Gauss-Newton iterations at most
  double initial_threshold_m = 3.0;         // correspondence gate at the first iteration [m] (>= expected drift)
  // While the estimator is unsure of its position (a provisional GNSS alignment), ICP also runs with a first gate of
  // this many of its position sigmas (the largest, from the LocalMap's covariance), up to max_initial_threshold_m,
  // and the better-supported result wins: surfaces further off than the gate give no correspondence, so ICP cannot
  // pull the keyframe to them. Measured on city-loops through the tracking service: an alignment 7 m off in height
  // (ray-traced GNSS) came in to 3.9 m with the 3 m gate (the ground beyond it), and stayed there for 45 s; vio-twin
  // 1.653 m, with a 10 m gate 0.468 m. 0: the fixed gate only.
  double initial_threshold_sigmas = 3.0;    // [1]
  double max_initial_threshold_m = 10.0;    // [m]
  double min_threshold_m = 0.25;            // the adaptive gate never shrinks below this [m] (~ twin point spacing / 2)
  double threshold_sigmas = 3.0;            // gate = this * robust sigma of the correspondence distances (KISS-ICP: 3)
  double convergence_translation_m = 1e-4;  // converged when the update's translation is below this [m] ...
  double convergence_rotation_deg = 1e-3;   // ... and its rotation below this [deg]
  // Also estimate a scale of the cloud about the keyframe (7-DoF ICP; IcpResult::scale), then dropped: the VIO cloud
  // carries the window's scale error, and rigid ICP turns it into a position error of the keyframe of (s - 1) x its
  // distance to the surfaces (city-survey: VIO scale +3 % / -3..-7 %, landmarks 70 m below -> registrations
  // +1.4 / -1.6 m in height). The information is then the Schur complement over the scale (less where it couples with
  // position).
  bool estimate_scale = true;
  // A slowly varying scale per vehicle (scale_tracker.hpp) as a prior on each 7-DoF ICP's log-scale, against surfaces
  // that moved since the twin was made. Its ln s wanders by a random walk of this [1/sqrt(s)]; 0: no prior.
  double scale_prior_walk = 0.003;
  double scale_prior_measurement_sigma = 0.006;  // each accepted registration's ln s as a measurement of it [-]
  // ... applied only to a keyframe whose covariance (LocalMap.T_WB_covariance) says the estimator has settled: while
  // the twin corrections are still reshaping its map, the VIO scale changes within seconds (scale_tracker.hpp).
  double scale_prior_max_heading_sigma_deg = 0.25;  // the keyframe's heading sigma must be below this [deg] ...
  double scale_prior_max_position_sigma_m = 0.25;   // ... and sqrt(trace) of its position covariance below this [m]
  // Heading search (yaw_search.hpp): when the estimator's heading sigma is above yaw_search_min_sigma_deg, ICP also
  // starts from headings rotated about the body by multiples of yaw_search_step_deg within +-min(3 sigma,
  // yaw_search_max_deg), and the start whose result the twin supports best wins.
  double yaw_search_min_sigma_deg = 1.0;  // [deg] heading sigma above which the search runs
  double yaw_search_step_deg = 2.0;       // [deg] spacing of the start headings (< the ~3 deg ICP converges from)
  double yaw_search_max_deg = 45.0;       // [deg] the starts span at most this either side (a provisional GNSS
                                          // alignment has a heading sigma up to 30 deg: 45 starts, ~0.1 s, once)
  double yaw_search_ambiguity = 0.9;      // a distinct heading with >= this x the best support: ambiguous (degenerate)

  // --- information (information.hpp), eqs. (8)-(10) ---
  WeightMode weights = WeightMode::kAdaptive;
  double paper_beta = 1.0;              // beta of eq. (10) [-]
  // adaptive: residual variance x this, because neighbouring landmarks and the twin's per-surface error are
  // correlated (N points are not N independent looks), and consecutive LocalMaps share most of their landmarks and
  // surfaces (10 s horizon, about a keyframe a second): the estimator fuses each registration as independent. Chosen
  // by measurement over city-loops, city-survey, city-long and city-long without / with other twin changes: ATE_p
  // mean 0.449 m at 10, 0.318 at 20, 0.298 at 40, 0.281 at 80 (but city-survey and the 10 s error worse than at 40)
  double correlation_inflation = 40.0;
  double min_sigma_m = 0.02;            // adaptive: floor of the residual sigma [m] (noise-free input stays finite)
  double degeneracy_threshold = 0.01;   // eigenvalue of the per-point normalized H below this: direction zeroed [-]
  // adaptive: the twin's own error per planar surface [m]. A twin's facade, roof or street is usually off as a whole
  // (a survey or modelling error of that surface), so the landmarks on one surface are not independent looks: with
  // this > 0 the inliers are grouped by the twin plane they matched (normals within surface_group_angle_deg, plane
  // offsets within surface_group_offset_m) and each plane's offset, N(0, this^2), is propagated to the correction
  // (information.hpp). A registration that rests on a few surfaces then weighs, and is judged, as uncertain as the
  // twin makes it. 0: off (the residual variance x correlation_inflation alone). 0.2 by measurement (vio-twin ATE_p
  // over city-loops with ideal and with tracked images, city-survey, delft-loops, city-long, tiny and the four
  // wrong-twin scenarios, summed: 2.825 m off, 2.677 m at 0.2, 2.613 m at 0.3 - but at 0.3 the removed-building twin
  // drew 29 of 59 accepted registrations > 0.5 m off, none at 0.2 -, 0.5 worse on city-loops and city-survey).
  double surface_error_m = 0.2;
  double surface_group_angle_deg = 10.0;  // [deg] normals of one plane differ by less than this
  double surface_group_offset_m = 0.3;    // [m] ... and their planes' offsets by less than this
  double fixed_rotation_information = 1e4;     // fixed: diagonal for rotation [1/rad^2]
  double fixed_translation_information = 1e2;  // fixed: diagonal for translation [1/m^2]

  // --- acceptance (registration.hpp) ---
  int min_inliers = 30;               // fewer inliers at the end: rejected
  double min_fitness = 0.3;           // inliers / source points below this: rejected [-]
  double max_rmse_m = 1.0;            // inlier point-to-plane RMSE above this: rejected [m] (0.3 and 0.5 refused
                                      // most VIO clouds on city-long / city-survey; the weight falls with the RMSE)
  int max_zero_directions = 2;        // more poorly observed directions than this: rejected (degenerate)
  // The registration's own predicted position sigma along the directions it observes (the largest; from the pseudo-
  // inverse of its information, geometry::observed_position_sigma_m) above this: rejected [m]. 0: off.
  double max_position_sigma_m = 0.0;
  double max_mahalanobis_sq = 22.46;  // correction vs the estimator's covariance: chi^2(6 dof) at 99.9 %
  // ... whose diagonal gets the registration's own uncertainty first (the twin's modelling error, ICP noise), so a
  // confident estimator does not reject corrections smaller than what registration can resolve:
  double mahalanobis_floor_m = 0.1;     // [m] added in quadrature to each position sigma
  double mahalanobis_floor_deg = 0.5;   // [deg] added in quadrature to each rotation sigma
  // persistence_gate.hpp: this many refusals by the Mahalanobis gate that agree within these tolerances over at least
  // persistent_span_s re-admit the last one (the estimator drifted and became overconfident); 0 turns it off.
  int persistent_corrections = 5;
  double persistent_tolerance_m = 0.3;    // [m] translation difference between the agreeing corrections
  double persistent_tolerance_deg = 1.0;  // [deg] rotation difference between them
  double persistent_tolerance_fraction = 0.1;  // translation tolerance at least this x the newest correction's [-]
  double persistent_span_s = 10.0;        // [s] the run spans at least this (local_map.horizon_s: other landmarks)
  // Acquisition (persistence_gate.hpp): while the estimator's heading sigma is above this, a correction larger than
  // acquisition_min_correction_m at the keyframe or acquisition_min_correction_deg is not accepted alone but must be
  // confirmed by the persistence gate's votes (0: off).
  double acquisition_heading_sigma_deg = 3.0;  // [deg] (the estimator declares its alignment below 3 deg)
  double acquisition_min_correction_m = 1.0;   // [m]
  double acquisition_min_correction_deg = 1.0;  // [deg]
  int acquisition_corrections = 3;     // agreeing results (the held one included) that confirm it ...
  double acquisition_span_s = 3.0;     // [s] ... over at least this

  CorrectionFault fault_correction_offset;  // YAML: faults: {correction_offset: {...}}

  bool operator==(const RegistrationConfig&) const = default;

  // Throws twinslam::InputError "SOURCE: registration key 'K': what" naming the first bad field.
  void validate(const std::string& source = "RegistrationConfig") const;
};

// Parses YAML text (`file` only names it in messages) over `base`; unknown keys and wrong types throw InputError
// naming the file, line and key. Not validated: the caller applies its overrides and calls validate().
RegistrationConfig parse_registration_config(const std::string& text, const std::string& file,
                                             const RegistrationConfig& base = {});
RegistrationConfig load_registration_config(const std::string& path, const RegistrationConfig& base = {});

}  // namespace twinslam::registration
