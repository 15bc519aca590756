#include "run_hooks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "twinslam/dds/convert.hpp"
#include "twinslam/geometry/information_order.hpp"

namespace twinslam::cli {

// RunRecord::odometry_faults() names the bits in this order.
static_assert(msg::ODOM_FAULT_IMU_REJECTED == 1 && msg::ODOM_FAULT_IMU_GAP == 2 && msg::ODOM_FAULT_FEW_FEATURES == 4 &&
              msg::ODOM_FAULT_FRAME_GAP == 8 && msg::ODOM_FAULT_GNSS_REJECTED == 16 &&
              msg::ODOM_FAULT_REGISTRATION_REFUSED == 32);

OdometryRecord to_record(const msg::Odometry& m) {
  const bool estimated = m.status() == msg::ODOM_TRACKING || m.status() == msg::ODOM_ALIGNED;
  return {m.stamp_ns(), dds::from_msg(m.T_WB()), dds::from_msg(m.T_LB()), m.estimator_ms(), estimated,
          m.status() == msg::ODOM_ALIGNED, m.faults()};
}

RegistrationRecord to_record(const msg::Registration& m) {
  RegistrationRecord r;
  r.stamp_ns = m.keyframe_stamp_ns();
  r.accepted = m.status() == msg::REG_ACCEPTED;
  r.reason = m.reason().empty() ? (r.accepted ? "accepted" : "rejected") : m.reason();
  r.rmse_m = m.rmse_m();
  r.inliers = m.inliers();
  r.fitness = m.fitness();
  r.time_ms = m.compute_ms();
  r.latency_ms = m.latency_ms();
  for (int i = 0; i < 6; ++i) r.info_eigenvalues[i] = m.information_eigenvalues()[i];
  std::array<double, 36> information{};
  std::copy(m.information().begin(), m.information().end(), information.begin());
  const geometry::Matrix6d I = geometry::from_row_major(information);
  r.sigma_m = I.allFinite() ? geometry::observed_position_sigma_m(I) : std::nan("");
  // The correction of the keyframe's pose: its position moves by dT c - c (c = pivot), its attitude by dR.
  const Eigen::Isometry3d T = dds::from_msg(m.correction_W());
  const Eigen::Vector3d c = dds::from_msg(m.pivot_W());
  r.dp_m = T * c - c;
  // Roll, pitch, yaw (ZYX) of the correction.
  const Eigen::Matrix3d R = T.linear();
  r.drpy_deg = Eigen::Vector3d(std::atan2(R(2, 1), R(2, 2)), std::asin(std::clamp(-R(2, 0), -1.0, 1.0)),
                               std::atan2(R(1, 0), R(0, 0))) * 180.0 / M_PI;
  return r;
}

MonitorHooks record_hooks(RunRecord& record, const std::string& vehicle, bool features,
                          std::function<double()> since_ms, std::atomic<std::size_t>& poses) {
  MonitorHooks hooks;
  hooks.vehicle = vehicle;
  hooks.image = [&record, since_ms](const msg::Image& m) { record.frame_in(m.stamp_ns(), since_ms()); };
  hooks.features = [&record, since_ms, features](const msg::FeatureFrame& m) {
    if (features) record.frame_in(m.stamp_ns(), since_ms());
    record.features(m.stamp_ns(), m.tracking_ms());
  };
  hooks.odometry = [&record, since_ms, &poses](const msg::Odometry& m) {
    record.odometry(to_record(m), since_ms());
    poses.fetch_add(1, std::memory_order_relaxed);
  };
  hooks.local_map = [&record, since_ms](const msg::LocalMap& m) {
    // The estimator sends its covariance once it has a world alignment: then the keyframe pose is in W.
    std::optional<Eigen::Isometry3d> T_WB;
    std::vector<std::uint64_t> ids;
    ids.reserve(m.landmarks().size());
    for (const msg::Landmark& l : m.landmarks()) ids.push_back(l.id());
    record.landmarks_seen(ids, m.keyframe_stamp_ns(), dds::from_msg(m.T_LB()).translation());
    if (!m.T_WB_covariance().empty()) {
      const Eigen::Isometry3d T_WL = dds::from_msg(m.T_WL());
      T_WB = T_WL * dds::from_msg(m.T_LB());
      std::vector<LandmarkRecord> in_W;
      in_W.reserve(m.landmarks().size());
      for (const msg::Landmark& l : m.landmarks()) {
        LandmarkRecord r;
        r.id = l.id();
        r.keyframe_stamp_ns = m.keyframe_stamp_ns();
        r.p_W = T_WL * dds::from_msg(l.p_L());
        r.quality = l.quality();
        in_W.push_back(r);
      }
      record.landmarks_W(in_W, T_WL);
    }
    record.local_map(m.keyframe_stamp_ns(), since_ms(), m.landmarks().size(), T_WB);
  };
  hooks.registration = [&record, since_ms](const msg::Registration& m) {
    record.registration(to_record(m), since_ms());
  };
  return hooks;
}

}  // namespace twinslam::cli
