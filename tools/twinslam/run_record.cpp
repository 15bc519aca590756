#include "run_record.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "twinslam/core/error.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::cli {

void RunRecord::frame_in(std::int64_t stamp_ns, double wall_ms) {
  std::lock_guard lock(mutex_);
  frame_wall_ms_.emplace(stamp_ns, wall_ms);
}

void RunRecord::features(std::int64_t stamp_ns, double tracking_ms) {
  std::lock_guard lock(mutex_);
  tracking_ms_[stamp_ns] = tracking_ms;
}

void RunRecord::odometry(const OdometryRecord& r, double wall_ms) {
  std::lock_guard lock(mutex_);
  const auto it = frame_wall_ms_.find(r.stamp_ns);
  // End to end: from the frame leaving ingest (as seen here) to its pose arriving here; -1 when unknown.
  odometry_.emplace_back(r, it == frame_wall_ms_.end() ? -1.0 : wall_ms - it->second);
}

void RunRecord::local_map(std::int64_t keyframe_stamp_ns, double wall_ms, std::size_t landmarks,
                          const std::optional<Eigen::Isometry3d>& T_WB_world) {
  std::lock_guard lock(mutex_);
  if (local_map_wall_ms_.emplace(keyframe_stamp_ns, wall_ms).second) local_map_sizes_.push_back(landmarks);
  if (T_WB_world) local_map_T_WB_.emplace(keyframe_stamp_ns, *T_WB_world);
}

void RunRecord::landmarks_seen(const std::vector<std::uint64_t>& ids, std::int64_t keyframe_stamp_ns,
                               const Eigen::Vector3d& p_LB) {
  std::lock_guard lock(mutex_);
  for (const std::uint64_t id : ids) {
    const auto [it, fresh] = first_seen_.emplace(id, std::make_pair(keyframe_stamp_ns, p_LB));
    if (!fresh && keyframe_stamp_ns < it->second.first) it->second = {keyframe_stamp_ns, p_LB};  // out of order
  }
}

void RunRecord::landmarks_W(const std::vector<LandmarkRecord>& landmarks, const Eigen::Isometry3d& T_WL) {
  std::lock_guard lock(mutex_);
  for (LandmarkRecord l : landmarks) {
    LandmarkRecord& kept = landmarks_W_[l.id];
    if (l.keyframe_stamp_ns < kept.keyframe_stamp_ns) continue;  // LocalMaps may arrive out of order
    const auto first = first_seen_.find(l.id);
    l.first_keyframe_stamp_ns = first != first_seen_.end() ? first->second.first : l.keyframe_stamp_ns;
    if (first != first_seen_.end()) l.observer_W = T_WL * first->second.second;
    kept = l;
  }
}

std::pair<std::size_t, std::size_t> RunRecord::local_map_landmarks() const {
  std::lock_guard lock(mutex_);
  if (local_map_sizes_.empty()) return {0, 0};
  std::vector<std::size_t> v = local_map_sizes_;
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v.back()};
}

void RunRecord::registration(RegistrationRecord r, double wall_ms) {
  std::lock_guard lock(mutex_);
  const auto it = local_map_wall_ms_.find(r.stamp_ns);
  r.pipeline_latency_ms = it == local_map_wall_ms_.end() ? std::nan("") : wall_ms - it->second;
  if (const auto pose = local_map_T_WB_.find(r.stamp_ns); pose != local_map_T_WB_.end()) r.keyframe_T_WB = pose->second;
  registrations_.push_back(std::move(r));
}

RunRecord::Latency RunRecord::pipeline_latency() const {
  std::lock_guard lock(mutex_);
  std::vector<double> v;
  for (const auto& r : registrations_)
    if (std::isfinite(r.pipeline_latency_ms)) v.push_back(r.pipeline_latency_ms);
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))]; };
  return {v.size(), at(0.5), at(0.99)};
}

std::map<std::string, std::size_t> RunRecord::odometry_faults() const {
  // The names of the estimator's heartbeat counters for each ODOM_FAULT_* bit (Estimation.idl), bit 0 first.
  static const char* const kNames[] = {"imu_rejected", "frames_with_imu_gap", "frames_few_features", "frame_gaps",
                                       "gnss_rejected", "registrations_refused"};
  std::map<std::string, std::size_t> out;
  std::lock_guard lock(mutex_);
  for (const auto& [o, _] : odometry_) {
    for (std::size_t bit = 0; bit < std::size(kNames); ++bit) {
      if (o.faults & (1u << bit)) ++out[kNames[bit]];
    }
  }
  return out;
}

std::size_t RunRecord::odometry_count() const {
  std::lock_guard lock(mutex_);
  return odometry_.size();
}

std::optional<std::int64_t> RunRecord::first_aligned_stamp_ns() const {
  std::lock_guard lock(mutex_);
  for (const auto& [o, _] : odometry_) {
    if (o.estimated && o.aligned) return o.stamp_ns;
  }
  return std::nullopt;
}

std::optional<std::int64_t> RunRecord::first_estimate_stamp_ns() const {
  std::lock_guard lock(mutex_);
  for (const auto& [o, _] : odometry_) {
    if (o.estimated) return o.stamp_ns;
  }
  return std::nullopt;
}

std::vector<std::pair<std::int64_t, std::int64_t>> RunRecord::out_of_world_after_alignment() const {
  std::lock_guard lock(mutex_);
  std::vector<std::pair<std::int64_t, std::int64_t>> stretches;
  bool seen_world = false, in_stretch = false;
  for (const auto& [o, _] : odometry_) {
    const bool in_world = o.estimated && o.aligned;
    seen_world = seen_world || in_world;
    if (!seen_world || in_world) {
      in_stretch = false;
      continue;
    }
    if (!in_stretch) stretches.emplace_back(o.stamp_ns, o.stamp_ns);
    stretches.back().second = o.stamp_ns;
    in_stretch = true;
  }
  return stretches;
}

std::vector<std::filesystem::path> RunRecord::write(const std::filesystem::path& dir) const {
  std::lock_guard lock(mutex_);
  std::vector<std::filesystem::path> written;
  const bool any_estimate =
      std::any_of(odometry_.begin(), odometry_.end(), [](const auto& entry) { return entry.first.estimated; });
  if (any_estimate) {
    Trajectory world, local;
    for (const auto& [o, _] : odometry_) {
      if (!o.estimated) continue;
      // A pose repeated for the same stamp (re-publication) keeps the first: TUM stamps must increase.
      if (!world.poses.empty() && o.stamp_ns <= world.poses.back().stamp_ns) continue;
      world.poses.push_back({o.stamp_ns, o.T_WB});
      local.poses.push_back({o.stamp_ns, o.T_LB});
    }
    write_tum(dir / "trajectory.tum", world);
    write_tum(dir / "trajectory_local.tum", local);
    written.push_back(dir / "trajectory.tum");
    written.push_back(dir / "trajectory_local.tum");
  }
  {
    std::ofstream f(dir / "timing.csv");
    if (!f) throw InputError((dir / "timing.csv").string() + ": cannot write");
    f << "stamp_ns,tracking_ms,estimator_ms,end_to_end_ms\n";
    for (const auto& [o, e2e] : odometry_) {
      const auto t = tracking_ms_.find(o.stamp_ns);
      char line[160];
      std::snprintf(line, sizeof(line), "%lld,%.3f,%.3f,%.3f\n", static_cast<long long>(o.stamp_ns),
                    t == tracking_ms_.end() ? 0.0 : t->second, o.estimator_ms, e2e);
      f << line;
    }
    written.push_back(dir / "timing.csv");
  }
  {
    std::ofstream f(dir / "registrations.csv");
    if (!f) throw InputError((dir / "registrations.csv").string() + ": cannot write");
    f << "stamp_ns,accepted,rmse_m,inliers,fitness,time_ms,ev1,ev2,ev3,ev4,ev5,ev6,dx_m,dy_m,dz_m,droll_deg,"
         "dpitch_deg,dyaw_deg,latency_ms,pipeline_latency_ms,reason,kf_x_m,kf_y_m,kf_z_m,kf_qx,kf_qy,kf_qz,kf_qw,"
         "sigma_m\n";
    for (const auto& r : registrations_) {
      f << r.stamp_ns << ',' << (r.accepted ? 1 : 0) << ',' << r.rmse_m << ',' << r.inliers << ',' << r.fitness << ','
        << r.time_ms;
      for (int i = 0; i < 6; ++i) f << ',' << r.info_eigenvalues[i];
      for (int i = 0; i < 3; ++i) f << ',' << r.dp_m[i];
      for (int i = 0; i < 3; ++i) f << ',' << r.drpy_deg[i];
      std::string reason = r.reason;
      std::replace(reason.begin(), reason.end(), ',', ';');  // one CSV field
      std::replace(reason.begin(), reason.end(), '\n', ' ');
      f << ',' << r.latency_ms << ',';
      if (std::isfinite(r.pipeline_latency_ms)) f << r.pipeline_latency_ms;
      f << ',' << reason;
      // The keyframe's pose from its LocalMap, which may reach this recorder after the registration (another reader).
      std::optional<Eigen::Isometry3d> kf = r.keyframe_T_WB;
      if (const auto pose = local_map_T_WB_.find(r.stamp_ns); !kf && pose != local_map_T_WB_.end()) kf = pose->second;
      if (kf) {
        const Eigen::Vector3d p = kf->translation();
        const Eigen::Quaterniond q(kf->linear());
        char pose[200];
        std::snprintf(pose, sizeof pose, ",%.6f,%.6f,%.6f,%.9f,%.9f,%.9f,%.9f", p.x(), p.y(), p.z(), q.x(), q.y(), q.z(),
                      q.w());
        f << pose;
      } else {
        f << ",,,,,,,";
      }
      f << ',' << r.sigma_m << '\n';
    }
    written.push_back(dir / "registrations.csv");
  }
  if (!landmarks_W_.empty()) {
    const auto file = dir / "landmarks.csv";
    std::ofstream f(file);
    if (!f) throw InputError(file.string() + ": cannot write");
    f << "#landmark_id,first_keyframe_stamp_ns,keyframe_stamp_ns,x_W [m],y_W [m],z_W [m],quality,observer_x_W [m],"
         "observer_y_W [m],observer_z_W [m]\n";
    for (const auto& [id, l] : landmarks_W_) {
      char row[200];
      std::snprintf(row, sizeof row, "%llu,%lld,%lld,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%.3f\n",
                    static_cast<unsigned long long>(id), static_cast<long long>(l.first_keyframe_stamp_ns),
                    static_cast<long long>(l.keyframe_stamp_ns), l.p_W.x(), l.p_W.y(), l.p_W.z(), l.quality,
                    l.observer_W.x(), l.observer_W.y(), l.observer_W.z());
      f << row;
    }
    written.push_back(file);
  }
  return written;
}

}  // namespace twinslam::cli
