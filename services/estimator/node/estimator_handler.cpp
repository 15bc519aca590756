#include "estimator_handler.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/geometry/information_order.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {
namespace {
using dds::to_msg;  // Eigen -> message, next to the status overload below

msg::OdometryStatus to_msg(EstimatorStatus s) {
  switch (s) {
    case EstimatorStatus::kTracking: return msg::ODOM_TRACKING;
    case EstimatorStatus::kReinitializing: return msg::ODOM_REINITIALIZING;
    case EstimatorStatus::kInitializing: break;
  }
  return msg::ODOM_INITIALIZING;
}

}  // namespace

EstimatorHandler::EstimatorHandler(dds::Counters& counters, const EstimatorNodeOptions& options)
    : counters_(counters),
      estimator_(options.estimator),
      fusion_(estimator_, options.fusion, options.initial_pose),
      enu_(options.origin ? std::make_unique<twin::EnuFrame>(*options.origin) : nullptr),
      options_(options) {
  if (options_.checkpoint_path.empty()) return;
  try {
    checkpoint_ = read_checkpoint(options_.checkpoint_path);
  } catch (const InputError& e) {
    spdlog::warn("checkpoint not used: {}", e.what());  // a checkpoint is an aid: a broken one only costs the resume
  }
}

void EstimatorHandler::resume_if_possible(std::int64_t frame_ns) {
  if (!checkpoint_) return;
  // The window's first keyframe needs IMU from its stamp on: a new process may see frames before its first sample.
  if (first_imu_ns_ < 0 || frame_ns < first_imu_ns_) return;
  if (estimator_.keyframe_count() > 0) {  // it started on its own (at rest) before IMU covered a frame
    checkpoint_.reset();
    return;
  }
  std::string why;
  const auto plan = plan_resume(*checkpoint_, frame_ns, options_.resume, &why);
  if (!plan) {
    spdlog::info("checkpoint {} not used: {}", options_.checkpoint_path, why);
    checkpoint_.reset();
    return;
  }
  checkpoint_.reset();
  estimator_.initialize_next_frame(plan->state_L, plan->sigmas);
  fusion_.start_from(plan->pose_W);
  counters_.add("resumed_from_checkpoint");
  spdlog::info("resuming from checkpoint {} ({:.2f} s old): position sigma {:.2f} m, heading sigma {:.1f} deg",
               options_.checkpoint_path, plan->age_s, plan->pose_W.sigmas->position_m,
               plan->pose_W.sigmas->yaw_rad * 180.0 / M_PI);
}

void EstimatorHandler::write_checkpoint_if_due(const FrameEstimate& e) {
  if (options_.checkpoint_path.empty() || e.status != EstimatorStatus::kTracking || !e.aligned ||
      !fusion_.world_declared()) {
    return;
  }
  if (checkpoint_written_ns_ >= 0 &&
      1e-9 * static_cast<double>(e.stamp_ns - checkpoint_written_ns_) < options_.checkpoint_every_s) {
    return;
  }
  EstimatorCheckpoint cp;
  cp.stamp_ns = e.stamp_ns;
  const Eigen::Isometry3d T_WB = e.T_WL * e.T_LB;
  cp.p_W = T_WB.translation();
  cp.q_WB = Eigen::Quaterniond(T_WB.linear());
  cp.v_W = e.T_WL.linear() * e.v_L;
  cp.bias = e.bias;
  // Sigmas of the pose in W ([dp_W, dtheta_B]) when the window has them; the defaults otherwise.
  if (const auto cov = estimator_.pose_covariance_world(e.stamp_ns); cov && cov->allFinite()) {
    // Within what read_checkpoint accepts (a sigma in (0, 1e6] m and (0, 360] deg).
    cp.position_sigma_m = std::clamp(std::sqrt(cov->topLeftCorner<3, 3>().diagonal().maxCoeff()), 1e-4, 1e6);
    cp.yaw_sigma_deg = std::clamp(std::sqrt(cov->bottomRightCorner<3, 3>().diagonal().maxCoeff()) * 180.0 / M_PI,
                                  1e-4, 360.0);
  }
  try {
    write_checkpoint(options_.checkpoint_path, cp);
    checkpoint_written_ns_ = e.stamp_ns;
    counters_.add("checkpoints_written");
  } catch (const std::exception& ex) {
    counters_.add("checkpoints_failed");
    spdlog::warn("{}", ex.what());
    checkpoint_written_ns_ = e.stamp_ns;  // retried at the next interval, not on every frame
  }
}

void EstimatorHandler::report_fusion() {
  // Heartbeat counters follow the fusion's own counts (added as deltas: Counters only adds).
  const GlobalFusionCounts& f = fusion_.counts();
  const MapRegistrationCounts& r = fusion_.registration_counts();
  const std::pair<const char*, unsigned long long> now[] = {
      {"alignments", f.alignments},
      {"realignments_declined", f.realignments_declined},
      {"provisional_alignments", f.provisional_alignments},
      {"registrations_fused", r.attached + r.reattached},
      {"registrations_reattached", r.reattached},
      {"registration_realignments", f.registration_realignments},
      {"registrations_dropped_by_realignment", r.dropped},
      {"registrations_unmatched", r.unmatched},
      {"registrations_before_alignment", f.registrations_before_alignment},
      {"registrations_unknown_keyframe", f.registrations_unknown_keyframe},
      {"registrations_invalid", f.registrations_invalid},
      {"registrations_refused", f.registrations_refused},
      {"gnss_jumps", fusion_.gnss_jump_counts().jumps},
      {"gnss_jumps_undone", fusion_.gnss_jump_counts().undone},
      {"gnss_jumps_held_out", fusion_.gnss_jump_counts().held_out},
  };
  for (const auto& [name, value] : now) {
    unsigned long long& last = reported_[name];
    if (value > last) counters_.add(name, value - last);
    last = value;
  }
}

std::uint32_t EstimatorHandler::frame_faults(const FrameEstimate& e) {
  std::uint32_t bits = 0;
  if (e.imu_gap_s > 0.0) {
    counters_.add("frames_with_imu_gap");
    bits |= msg::ODOM_FAULT_IMU_GAP;
  }
  if (e.few_features) {
    counters_.add("frames_few_features");
    bits |= msg::ODOM_FAULT_FEW_FEATURES;
  }
  return bits;
}

void EstimatorHandler::log_camera_calibration(std::int64_t stamp_ns) {
  // Every 30 s of data: what the online calibration made of the camera rotation (camera_calibration.hpp).
  const SlidingWindowConfig& c = estimator_.config();
  if ((c.camera_rotation_sigma_deg <= 0.0 && !c.estimates_lens()) ||
      stamp_ns - calibration_logged_ns_ < 30'000'000'000) {
    return;
  }
  calibration_logged_ns_ = stamp_ns;
  if (c.estimates_lens()) {
    const std::array<double, 4> lens = estimator_.lens_correction();
    spdlog::info("lens correction at {:.1f} s: focal {:+.4f} %, k1 {:+.5f}, principal point ({:+.3f}, {:+.3f}) px",
                 1e-9 * stamp_ns, 100.0 * lens[0], lens[1], lens[2] * c.focal_px, lens[3] * c.focal_px);
    return;
  }
  const Eigen::Matrix3d R_C0C = estimator_.config().T_BC.linear().transpose() * estimator_.camera_extrinsics().linear();
  const Eigen::Vector3d phi_deg = geometry::so3_log(R_C0C) * 180.0 / M_PI;
  spdlog::info("camera rotation correction at {:.1f} s: ({:.3f}, {:.3f}, {:.3f}) deg (camera axes)", 1e-9 * stamp_ns,
               phi_deg.x(), phi_deg.y(), phi_deg.z());
}

void EstimatorHandler::apply(const GlobalInput& input) {
  // On the worker thread, in stamp order relative to the frames.
  if (const auto* r = std::get_if<msg::Registration>(&input)) {
    counters_.add("registration_in");
    std::array<double, 36> info{};
    std::copy(r->information().begin(), r->information().end(), info.begin());
    const unsigned long long refused_before = fusion_.counts().registrations_refused;
    const std::string problem =
        fusion_.on_registration(r->keyframe_stamp_ns(), r->status() == msg::REG_ACCEPTED,
                                dds::from_msg(r->correction_W()),
                                geometry::from_row_major(info),  // (rotation, translation) as on the wire
                                r->readmitted());
    if (!problem.empty()) spdlog::warn("registration for keyframe {}: {}; not fused", r->keyframe_stamp_ns(), problem);
    if (fusion_.counts().registrations_refused > refused_before) faults_.fetch_or(msg::ODOM_FAULT_REGISTRATION_REFUSED);
    return;
  }
  const auto& g = std::get<msg::GnssFix>(input);
  counters_.add("gnss_in");
  if (!enu_) return;  // no origin: W is unknown, the fix cannot be used
  const Eigen::Vector3d p_W = enu_->from_lla(g.latitude_deg(), g.longitude_deg(), g.altitude_m());
  const Eigen::Matrix3d cov = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(g.covariance_enu_m2().data());
  if (p_W.allFinite() && cov.allFinite()) {
    const GnssJumpCounts before = fusion_.gnss_jump_counts();
    fusion_.on_gnss(g.stamp_ns(), p_W, cov);
    const GnssJumpCounts& after = fusion_.gnss_jump_counts();
    if (after.refused > before.refused) {
      counters_.add("gnss_rejected");
      faults_.fetch_or(msg::ODOM_FAULT_GNSS_REJECTED);
    }
    if (after.jumps > before.jumps) {
      spdlog::warn("GNSS fix at {}: a jump (its step exceeds the VIO's motion by more than fusion.gnss_jump_sigmas of "
                   "the fixes' sigmas); fixes refused until it is undone or fusion.gnss_jump_hold_s passes",
                   g.stamp_ns());
    }
    if (after.undone > before.undone) spdlog::info("GNSS fix at {}: the jump was undone; fixes used again", g.stamp_ns());
    if (after.held_out > before.held_out) {
      spdlog::warn("GNSS fix at {}: a jump lasted fusion.gnss_jump_hold_s; its level is used from now on", g.stamp_ns());
    }
  } else {
    counters_.add("gnss_rejected");
    faults_.fetch_or(msg::ODOM_FAULT_GNSS_REJECTED);
  }
}

EstimatorHandler::Output EstimatorHandler::handle(const msg::FeatureFrame& frame, std::vector<ImuSample>&& new_imu,
                                                  std::vector<GlobalInput>&& global) {
  for (const auto& g : global) apply(g);
  if (frame_gaps_.on_frame(frame.stamp_ns())) {
    counters_.add("frame_gaps");
    faults_.fetch_or(msg::ODOM_FAULT_FRAME_GAP);
  }
  for (const auto& s : new_imu) {
    if (first_imu_ns_ < 0 || s.stamp_ns < first_imu_ns_) first_imu_ns_ = s.stamp_ns;
    try {
      estimator_.add_imu(s);
    } catch (const InputError& e) {
      counters_.add("imu_rejected");
      faults_.fetch_or(msg::ODOM_FAULT_IMU_REJECTED);
      spdlog::warn("imu: {}", e.what());
    }
  }
  return process(frame);
}

EstimatorHandler::Output EstimatorHandler::process(const msg::FeatureFrame& m) {
  std::vector<FeatureBearing> features;
  features.reserve(m.features().size());
  for (const auto& f : m.features()) {
    const Eigen::Vector3d b(f.bearing_C().x(), f.bearing_C().y(), f.bearing_C().z());
    if (b.allFinite() && b.norm() > 0.5) features.push_back({static_cast<std::int64_t>(f.id()), b.normalized()});
  }
  Output out;
  try {
    resume_if_possible(m.stamp_ns());
    const FrameEstimate e = estimator_.add_frame(m.stamp_ns(), features);
    fusion_.after_frame(e, estimator_.local_map());
    report_fusion();
    write_checkpoint_if_due(e);
    msg::Odometry odom;
    odom.vehicle_id(m.vehicle_id());
    odom.stamp_ns(m.stamp_ns());
    odom.seq(odom_seq_++);
    // T_WB = T_WL T_LB in W once the alignment is declared (ODOM_ALIGNED: global_fusion.hpp). Before that T_WL is
    // the identity guess (T_WB equals T_LB) or a provisional alignment that registration is still refining.
    const bool aligned = e.aligned && fusion_.world_declared() && e.status == EstimatorStatus::kTracking;
    odom.status(aligned ? msg::ODOM_ALIGNED : to_msg(e.status));
    // vio-gnss-loose: the loose graph's alignment, the window's T_WL otherwise.
    const Eigen::Isometry3d T_WL = fusion_.output_T_WL().value_or(e.T_WL);
    odom.T_LB(to_msg(e.T_LB));
    odom.T_WL(to_msg(T_WL));
    odom.T_WB(to_msg(Eigen::Isometry3d(T_WL * e.T_LB)));
    odom.v_L(to_msg(e.v_L));
    odom.bias_gyro(to_msg(e.bias.gyro));
    odom.bias_accel(to_msg(e.bias.accel));
    odom.estimator_ms(e.estimator_ms);
    odom.faults(faults_.exchange(0) | frame_faults(e));
    out.odometry = odom;
    counters_.add("odometry_out");
    if (e.init_timed_out && counters_.get("init_timeout_reported") == 0) {
      counters_.add("init_timeout_reported");
      spdlog::warn("neither rest nor a motion initialization succeeded within init_timeout_s");
    }
    log_camera_calibration(m.stamp_ns());
    if (const auto& map = estimator_.local_map()) {
      out.local_map = local_map_message(*map, m.vehicle_id());
      counters_.add("local_maps_out");
    }
  } catch (const InputError& e) {
    counters_.add("frames_rejected");
    spdlog::warn("feature frame {}: {}", m.stamp_ns(), e.what());
  } catch (const std::exception& e) {
    // An internal failure on one frame must not stop the service (nor lockstep replay, which waits for the ack).
    counters_.add("frames_failed");
    spdlog::error("feature frame {}: estimator failed: {}", m.stamp_ns(), e.what());
  }
  return out;
}

msg::LocalMap EstimatorHandler::local_map_message(const LocalMapEstimate& map, const std::string& vehicle_id) {
  msg::LocalMap lm;
  lm.vehicle_id(vehicle_id);
  lm.keyframe_stamp_ns(map.keyframe_stamp_ns);
  lm.seq(map_seq_++);
  lm.T_LB(to_msg(map.T_LB));
  lm.T_WL(to_msg(map.T_WL));
  lm.landmarks().reserve(map.landmarks.size());
  for (const auto& l : map.landmarks) {
    msg::Landmark ml;
    ml.id(static_cast<unsigned long long>(l.id));
    ml.p_L(to_msg(l.p_L));
    ml.quality(static_cast<float>(l.quality));
    const Eigen::Matrix3d& c = l.cov_L;
    ml.cov_L({static_cast<float>(c(0, 0)), static_cast<float>(c(0, 1)), static_cast<float>(c(0, 2)),
              static_cast<float>(c(1, 1)), static_cast<float>(c(1, 2)), static_cast<float>(c(2, 2))});
    lm.landmarks().push_back(ml);
  }
  // Once in W, the keyframe's covariance lets registration gate a correction by the estimator's own uncertainty.
  if (const auto c = fusion_.published_covariance(map.keyframe_stamp_ns)) {
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 6; ++k) lm.T_WB_covariance().push_back((*c)(r, k));
  }
  return lm;
}

}  // namespace twinslam::estimator
