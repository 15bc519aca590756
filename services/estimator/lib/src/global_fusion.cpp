#include "twinslam/estimator/global_fusion.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/map_registration_factor.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kDegToRad = 0.017453292519943295;
// Floors of the re-opened alignment's prior: what one registration resolves (bench_registration_floor: 0.2-0.5 m).
constexpr double kReopenMinSigma_m = 0.5, kReopenMinSigma_deg = 0.5;
constexpr std::size_t kPublishedKept = 400;  // LocalMaps remembered for late registrations (~2 min of keyframes)

// How far a correction (a transform of W) moves the keyframe body at p_WB [m] and turns its heading [rad].
struct CorrectionSize {
  double position_m, yaw_rad;
};
CorrectionSize correction_size(const Eigen::Isometry3d& correction_W, const Eigen::Vector3d& p_WB) {
  const Eigen::Matrix3d dR = correction_W.linear();
  return {(correction_W * p_WB - p_WB).norm(), std::abs(std::atan2(dR(1, 0), dR(0, 0)))};
}

// The sigmas of the T_WL prior a GNSS fit sets: the fit's own (largest position sigma, heading) times the scale.
WorldAlignmentSigmas prior_sigmas(const GlobalFusionConfig& config, const WorldAlignment4Dof& fit) {
  WorldAlignmentSigmas sigmas;
  sigmas.position_m = config.gnss_alignment_sigma_scale * std::sqrt(fit.covariance.topLeftCorner<3, 3>().diagonal().maxCoeff());
  sigmas.yaw_rad = config.gnss_alignment_sigma_scale * fit.yaw_sigma_deg * kDegToRad;
  return sigmas;
}

}  // namespace

void GlobalFusionConfig::validate() const {
  const std::pair<const char*, double> positive[] = {
      {"initial_pose_position_sigma_m", initial_pose_position_sigma_m},
      {"initial_pose_yaw_sigma_deg", initial_pose_yaw_sigma_deg},
      {"gnss_alignment_sigma_scale", gnss_alignment_sigma_scale},
      {"realign_min_correction_m", realign_min_correction_m},
      {"realign_min_correction_deg", realign_min_correction_deg},
      {"declare_max_correction_m", declare_max_correction_m}};
  if (!(provisional_yaw_sigma_deg >= 0.0) || !std::isfinite(provisional_yaw_sigma_deg)) {
    throw InputError("global fusion: provisional_yaw_sigma_deg must be >= 0");
  }
  for (const auto& [name, v] : positive) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(std::string("global fusion: ") + name + " must be > 0");
  }
  if (declare_agreeing_registrations < 0) {
    throw InputError("global fusion: declare_agreeing_registrations must be >= 0");
  }
  if (!(gnss_correlation_s >= 0.0) || !std::isfinite(gnss_correlation_s)) {
    throw InputError("global fusion: gnss_correlation_s must be >= 0");
  }
  if (!(realign_after_s >= 0.0) || !std::isfinite(realign_after_s)) {
    throw InputError("global fusion: realign_after_s must be >= 0");
  }
  if (fuse_gnss_loose && fuse_gnss) {
    throw InputError("global fusion: fuse_gnss_loose and fuse_gnss exclude each other (loose or tight GNSS)");
  }
  if (fuse_gnss_loose && !align_from_gnss) {
    throw InputError("global fusion: fuse_gnss_loose needs align_from_gnss (the graph starts from that alignment)");
  }
  aligner.validate();
  registration_gate.validate();
  gnss_jump.validate();
  loose.validate();
  registration.validate();
  gnss.validate();
}

GlobalFusion::GlobalFusion(SlidingWindowEstimator& estimator, const GlobalFusionConfig& config,
                           std::optional<InitialPose> initial_pose)
    : estimator_(estimator),
      config_(config),
      initial_pose_(initial_pose),
      provider_(std::make_shared<MapRegistrationProvider>(config.registration)),
      gnss_provider_(std::make_shared<GnssProvider>(config.gnss)),
      aligner_(config.aligner),
      gnss_jump_(config.gnss_jump),
      loose_(config.loose) {
  config_.validate();
  if (config_.fuse_registrations) estimator_.add_factor_provider(provider_);
  if (config_.fuse_gnss) estimator_.add_factor_provider(gnss_provider_);
}

void GlobalFusion::on_gnss(std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const Eigen::Matrix3d& cov_W) {
  ++counts_.gnss_in;
  // The body position at the fix's stamp from the last estimate and its velocity (the fix is at most one frame
  // interval away: side inputs come with the first frame at or after their stamp).
  std::optional<Eigen::Vector3d> p_L;
  if (last_frame_ && last_frame_->status == EstimatorStatus::kTracking) {
    const double dt = 1e-9 * static_cast<double>(stamp_ns - last_frame_->stamp_ns);
    p_L = last_frame_->T_LB.translation() + last_frame_->v_L * dt;
  }
  if (!gnss_jump_.accept(stamp_ns, p_W, cov_W, p_L)) return;  // used for nothing, not even the correlation time
  const double interval_s = last_gnss_ns_ < 0 ? 0.0 : 1e-9 * static_cast<double>(stamp_ns - last_gnss_ns_);
  last_gnss_ns_ = stamp_ns;
  // Time-correlated errors: the covariance of one independent fix per gnss_correlation_s (fit and window terms).
  const Eigen::Matrix3d cov_eff =
      interval_s > 0.0 ? std::max(1.0, config_.gnss_correlation_s / interval_s) * cov_W : cov_W;
  if (config_.fuse_gnss) {
    try {
      gnss_provider_->add_fix(stamp_ns, p_W, cov_eff);
    } catch (const InputError&) {
      // counted as received (gnss_in) but not fused: no usable covariance
    }
  }
  if (config_.fuse_gnss_loose) loose_.add_fix(stamp_ns, p_W, cov_eff);
  if (!config_.align_from_gnss || !p_L) return;
  AlignmentPair pair;
  pair.p_L = *p_L;
  pair.p_W = p_W;
  pair.cov_W = cov_eff;
  try {
    aligner_.add(pair);
    ++counts_.gnss_paired;
  } catch (const InputError&) {
    return;  // a fix without a usable covariance: counted as received, not paired
  }
  const bool outage = declared_ && config_.realign_after_s > 0.0 && last_accepted_ns_ >= 0 &&
                      1e-9 * static_cast<double>(stamp_ns - last_accepted_ns_) > config_.realign_after_s;
  if (!declared_ || outage) try_align(stamp_ns);
}

void GlobalFusion::try_align(std::int64_t stamp_ns) {
  const auto a = aligner_.solve();
  if (!a) return;
  if (!declared_) {
    // Not in W yet. Once a registration has acted on a provisional T_WL, the window's own heading sigma decides
    // (check_declaration); a GNSS fit that converges first still declares it, replacing T_WL only if it is more
    // certain than the window (registrations weighted as eq. 10 can leave the heading at 3-10 deg for minutes).
    // Before any registration, a converged fit is used and declared, and a fit that is only provisional starts T_WL,
    // or replaces a provisional one it is at least twice as certain as in heading.
    if (aligned_ && counts_.registrations_accepted > accepted_at_provisional_) {
      if (!a->converged) return;
      if (realignment_helps(prior_sigmas(config_, *a))) {
        set_from_fit(*a, stamp_ns, true);
      } else if (registrations_agree()) {
        declared_ = true;
        aligner_.clear();
      }
      return;
    }
    const double limit = aligned_ ? 0.5 * provisional_yaw_sigma_deg_ : config_.provisional_yaw_sigma_deg;
    const bool usable = a->pairs >= static_cast<std::size_t>(config_.aligner.min_pairs) &&
                        a->span_m >= config_.aligner.min_span_m && a->yaw_sigma_deg < limit;
    if (a->converged || usable) set_from_fit(*a, stamp_ns, a->converged);
    return;
  }
  if (!a->converged) return;
  if (!realignment_helps(prior_sigmas(config_, *a))) {
    // Measured on city-loops: after 40 s without an accepted registration the estimate was 0.8 m / 0.06 deg off,
    // and replacing its T_WL by the fit of 150 s of fixes (biased by slowly varying GNSS errors) moved it to
    // 1.3 m / 1.5 deg. Only a fit more certain than the estimate replaces it; the next try is realign_after_s later.
    ++counts_.realignments_declined;
    last_accepted_ns_ = stamp_ns;
    return;
  }
  set_from_fit(*a, stamp_ns, true);
}

void GlobalFusion::set_from_fit(const WorldAlignment4Dof& fit, std::int64_t stamp_ns, bool declared) {
  estimator_.set_world_alignment(fit.T_WL, prior_sigmas(config_, fit));
  last_alignment_ = fit;
  aligned_ = true;
  declared_ = declared;
  last_accepted_ns_ = stamp_ns;
  recent_corrections_m_.clear();  // they were measured against the T_WL replaced here
  ++counts_.alignments;
  if (declared) {
    aligner_.clear();  // a later re-alignment uses fixes after this one only
  } else {
    ++counts_.provisional_alignments;  // the fixes stay: a better fit of more of them may replace it
    provisional_yaw_sigma_deg_ = fit.yaw_sigma_deg;
    accepted_at_provisional_ = counts_.registrations_accepted;
  }
}

void GlobalFusion::check_declaration() {
  if (!aligned_ || declared_ || counts_.registrations_accepted == accepted_at_provisional_) return;
  const auto cov = estimator_.world_alignment_covariance();  // [p_WL, yaw_WL]
  if (!cov) return;
  const double yaw_sigma_deg = std::sqrt(std::max((*cov)(3, 3), 0.0)) / kDegToRad;
  if (yaw_sigma_deg > config_.aligner.converged_yaw_sigma_deg || !registrations_agree()) return;
  declared_ = true;
  aligner_.clear();
}

bool GlobalFusion::registrations_agree() const {
  const auto n = static_cast<std::size_t>(config_.declare_agreeing_registrations);
  if (recent_corrections_m_.size() < n) return false;
  return std::all_of(recent_corrections_m_.end() - static_cast<std::ptrdiff_t>(n), recent_corrections_m_.end(),
                     [&](double m) { return m <= config_.declare_max_correction_m; });
}

std::optional<Eigen::Matrix<double, 6, 6>> GlobalFusion::published_covariance(std::int64_t keyframe_stamp_ns) const {
  const auto it = published_.find(keyframe_stamp_ns);
  return it == published_.end() ? std::nullopt : it->second.covariance;
}

std::optional<Eigen::Isometry3d> GlobalFusion::output_T_WL() const {
  if (config_.fuse_gnss_loose && loose_.started()) return loose_.T_WL();
  return std::nullopt;
}

bool GlobalFusion::realignment_helps(const WorldAlignmentSigmas& fit) const {
  // The estimator's own uncertainty of the newest pose in W, as registration sees it: (rotation about W's axes,
  // position in W).
  const auto cov_pW_thetaB = last_frame_ ? estimator_.pose_covariance_world(last_frame_->stamp_ns) : std::nullopt;
  if (!cov_pW_thetaB) return true;  // nothing to compare with: the estimate is not worth keeping
  const Eigen::Isometry3d T_WB = estimator_.world_alignment() * last_frame_->T_LB;
  const Eigen::Matrix<double, 6, 6> cov = to_registration_order(*cov_pW_thetaB, T_WB.linear());
  const double yaw_sigma_rad = std::sqrt(std::max(cov(2, 2), 0.0));
  const double horizontal_sigma_m = std::sqrt(std::max(std::max(cov(3, 3), cov(4, 4)), 0.0));
  return fit.yaw_rad < yaw_sigma_rad && fit.position_m < horizontal_sigma_m;
}

std::string GlobalFusion::on_registration(std::int64_t keyframe_stamp_ns, bool accepted,
                                          const Eigen::Isometry3d& correction_W,
                                          const Eigen::Matrix<double, 6, 6>& information, bool readmitted) {
  ++counts_.registrations_in;
  if (!accepted || !config_.fuse_registrations) return "";
  if (std::string problem = registration_problem(correction_W, information); !problem.empty()) {
    ++counts_.registrations_invalid;  // from the wire: never into the window
    return problem;
  }
  if (!aligned_) {
    // Computed against a T_WL nobody had aligned yet (the identity guess): where its ICP converged means nothing.
    ++counts_.registrations_before_alignment;
    return "";
  }
  const auto it = published_.find(keyframe_stamp_ns);
  if (it == published_.end()) {
    ++counts_.registrations_unknown_keyframe;  // not a LocalMap this estimator published (or too old)
    return "";
  }
  const auto& [T_LB, T_WL, covariance] = it->second;
  // Refused by the gate below or not, it says whether the twin agrees with the estimate (registrations_agree).
  recent_corrections_m_.push_back(correction_size(correction_W, (T_WL * T_LB).translation()).position_m);
  if (recent_corrections_m_.size() > static_cast<std::size_t>(config_.declare_agreeing_registrations)) {
    recent_corrections_m_.pop_front();
  }
  if (std::string refusal = registration_refusal(
          config_.registration_gate, {correction_W, T_WL * T_LB, covariance, readmitted, world_declared()});
      !refusal.empty()) {
    ++counts_.registrations_refused;
    return refusal;
  }
  if (readmitted && config_.realign_on_readmitted_registration && reopening_warranted(correction_W, T_WL * T_LB)) {
    reopen_alignment(correction_W, T_WL, T_LB);
  }
  provider_->add(map_registration_from_correction(keyframe_stamp_ns, T_WL * T_LB, correction_W, information), T_LB);
  ++counts_.registrations_accepted;
  last_accepted_ns_ = keyframe_stamp_ns;
  return "";
}

bool GlobalFusion::reopening_warranted(const Eigen::Isometry3d& correction_W, const Eigen::Isometry3d& T_WB) const {
  const CorrectionSize size = correction_size(correction_W, T_WB.translation());
  return size.position_m > config_.realign_min_correction_m ||
         size.yaw_rad > config_.realign_min_correction_deg * kDegToRad;
}

void GlobalFusion::reopen_alignment(const Eigen::Isometry3d& correction_W, const Eigen::Isometry3d& T_WL,
                                    const Eigen::Isometry3d& T_LB) {
  // The correction moves W's points as the estimate saw them onto the twin, so the alignment that puts this keyframe
  // where the twin says is dT T_WL (its heading kept, roll and pitch dropped: L and W are gravity-aligned). How far
  // that is from the estimate is how wrong the estimator was while sure of itself: the new prior's sigmas.
  const Eigen::Isometry3d T_WL_new = correction_W * T_WL;
  const CorrectionSize size = correction_size(correction_W, (T_WL * T_LB).translation());
  WorldAlignmentSigmas sigmas;
  sigmas.position_m = std::max(kReopenMinSigma_m, size.position_m);
  sigmas.yaw_rad = std::max(kReopenMinSigma_deg * kDegToRad, size.yaw_rad);
  estimator_.set_world_alignment(T_WL_new, sigmas);
  provider_->drop_all();
  recent_corrections_m_.clear();
  ++counts_.registration_realignments;
}

void GlobalFusion::after_frame(const FrameEstimate& estimate, const std::optional<LocalMapEstimate>& local_map) {
  last_frame_ = estimate;
  if (estimate.status != EstimatorStatus::kTracking) {
    aligned_ = estimator_.world_aligned();  // a reset forgets T_WL: align again
    if (!aligned_) {
      aligner_.clear();
      declared_ = false;
    }
    loose_.stop();  // the VIO frame L starts anew
    return;
  }
  if (config_.fuse_gnss_loose) {
    loose_.add_odometry(estimate.stamp_ns, estimate.T_LB);
    if (!loose_.started() && world_declared()) loose_.start(estimator_.world_alignment());
  }
  if (initial_pose_ && !aligned_) {
    // T_WB(now) = T_WL T_LB(now) with the user's position and heading: T_WL = (Rz(yaw - yaw_LB), p - Rz p_LB).
    const Eigen::Matrix3d R = estimate.T_LB.linear();
    const double yaw_LB = std::atan2(R(1, 0), R(0, 0));
    Eigen::Isometry3d T_WL = Eigen::Isometry3d::Identity();
    T_WL.linear() = Eigen::AngleAxisd(initial_pose_->yaw_deg * kDegToRad - yaw_LB, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T_WL.translation() = initial_pose_->p_W - T_WL.linear() * estimate.T_LB.translation();
    const WorldAlignmentSigmas sigmas = initial_pose_->sigmas.value_or(WorldAlignmentSigmas{
        config_.initial_pose_position_sigma_m, config_.initial_pose_yaw_sigma_deg * kDegToRad});
    estimator_.set_world_alignment(T_WL, sigmas);
    aligned_ = true;
    declared_ = sigmas.yaw_rad / kDegToRad <= config_.aligner.converged_yaw_sigma_deg;
    accepted_at_provisional_ = counts_.registrations_accepted;
    last_accepted_ns_ = estimate.stamp_ns;
    ++counts_.alignments;
  }
  if (local_map) {
    check_declaration();  // a keyframe: the registrations of earlier ones are in the window
    // GNSS terms join once the alignment is declared: on a provisional T_WL (heading sigma up to 30 deg) their
    // weak, correlation-inflated fixes would hold the heading where the first fit put it.
    gnss_provider_->set_active(world_declared());
    Published& published = published_[local_map->keyframe_stamp_ns];
    published = {local_map->T_LB, local_map->T_WL, std::nullopt};
    if (config_.fuse_registrations && estimator_.world_aligned()) {
      if (const auto cov = estimator_.pose_covariance_world(local_map->keyframe_stamp_ns)) {
        published.covariance = to_registration_order(*cov, (local_map->T_WL * local_map->T_LB).linear());
      }
    }
    if (published_.size() > kPublishedKept) published_.erase(published_.begin());
  }
}

}  // namespace twinslam::estimator
