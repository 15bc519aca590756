#pragma once
// What `twinslam run` writes besides run.json (CONTRACTS.md "Run outputs"): trajectory.tum (T_WB as estimated live),
// trajectory_local.tum (T_LB), timing.csv and registrations.csv. Pure bookkeeping, fed from the recorder's DDS
// callbacks; all times it measures come from this one process's clock, so nothing assumes services share a clock.
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace twinslam::cli {

struct OdometryRecord {
  std::int64_t stamp_ns = 0;
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_LB = Eigen::Isometry3d::Identity();
  double estimator_ms = 0;
  bool estimated = true;  // false while initializing: the pose is a placeholder, kept out of the trajectories
  bool aligned = false;   // ODOM_ALIGNED: T_WB is in the world frame W
  std::uint32_t faults = 0;  // Odometry.faults: ODOM_FAULT_* bits
};

struct RegistrationRecord {
  std::int64_t stamp_ns = 0;
  bool accepted = false;
  double rmse_m = 0, fitness = 0, time_ms = 0;
  std::uint32_t inliers = 0;
  Eigen::Matrix<double, 6, 1> info_eigenvalues = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Vector3d dp_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d drpy_deg = Eigen::Vector3d::Zero();  // roll, pitch, yaw of the correction [deg]
  double latency_ms = 0;  // LocalMap arrival -> Registration publication on the registration host [ms]
  // LocalMap arrival here -> Registration arrival here [ms] (this process runs beside the estimator, so this is the
  // age of a result when the estimator can fuse it: transport both ways, queueing and compute); NaN if the LocalMap
  // was not seen.
  double pipeline_latency_ms = 0;
  std::string reason;     // "accepted", or why it was rejected (one line, no commas written)
  // The largest position sigma the registration's information states along the directions it observes
  // (geometry::observed_position_sigma_m) [m]; 0 when it sent none (rejected).
  double sigma_m = 0;
  // The keyframe pose T_WB the LocalMap carried (T_WL T_LB), when the estimator had a world alignment then (it sent
  // its covariance): what the correction applies to. Filled by registration() from the LocalMap seen here.
  std::optional<Eigen::Isometry3d> keyframe_T_WB;
};

// A landmark of a LocalMap in W (T_WL p_L) while the estimator had a world alignment: landmarks.csv keeps the
// latest of each id, the cloud `twinslam export --ply` writes.
struct LandmarkRecord {
  std::uint64_t id = 0;
  std::int64_t keyframe_stamp_ns = 0;  // of the LocalMap that carried it last
  std::int64_t first_keyframe_stamp_ns = 0;  // of the first LocalMap that carried it (about when it was seen)
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // [m]
  // Where it was seen from: the first carrying LocalMap's keyframe position, in W through the latest T_WL (so it and
  // p_W share one alignment even when that LocalMap came before the world alignment).
  Eigen::Vector3d observer_W = Eigen::Vector3d::Zero();  // [m]
  float quality = 0;                             // 0..1 (Landmark.quality)
};

class RunRecord {
 public:
  // Thread-safe: called from DDS listener threads. `wall_ms` is this process's steady clock in ms.
  void frame_in(std::int64_t stamp_ns, double wall_ms);                 // image or feature frame sent by ingest
  void features(std::int64_t stamp_ns, double tracking_ms);
  void odometry(const OdometryRecord& r, double wall_ms);
  // A LocalMap on the wire; T_WB_world: its keyframe pose when it was in W (the estimator had a world alignment).
  void local_map(std::int64_t keyframe_stamp_ns, double wall_ms, std::size_t landmarks,
                 const std::optional<Eigen::Isometry3d>& T_WB_world = std::nullopt);
  // Every LocalMap's landmarks (ids, keyframe stamp and position p_LB of its keyframe in L): remembers where each id
  // was first seen from. Then, while aligned, their estimate in W (T_WL: the LocalMap's alignment); a later
  // LocalMap's estimate of an id replaces the earlier. Only landmarks estimated in W are written.
  void landmarks_seen(const std::vector<std::uint64_t>& ids, std::int64_t keyframe_stamp_ns,
                      const Eigen::Vector3d& p_LB);
  void landmarks_W(const std::vector<LandmarkRecord>& landmarks, const Eigen::Isometry3d& T_WL);
  void registration(RegistrationRecord r, double wall_ms);  // fills r.pipeline_latency_ms and r.keyframe_T_WB
  // Median and 99th percentile of pipeline_latency_ms over the registrations whose LocalMap was seen [ms].
  struct Latency {
    std::size_t count = 0;
    double median_ms = 0, p99_ms = 0;
  };
  Latency pipeline_latency() const;
  // Median and largest number of landmarks per LocalMap (registration's source cloud before preprocessing).
  std::pair<std::size_t, std::size_t> local_map_landmarks() const;

  std::size_t odometry_count() const;
  // Per bit of Odometry.faults: how many poses carried it, named like the estimator's counter of it.
  std::map<std::string, std::size_t> odometry_faults() const;
  // Stamp of the first pose in W (ODOM_ALIGNED) and of the first estimated pose, if any.
  std::optional<std::int64_t> first_aligned_stamp_ns() const;
  std::optional<std::int64_t> first_estimate_stamp_ns() const;
  // After the first pose in W: the stamps [first, last] of each stretch of poses that were not in W (an estimator that
  // restarted or re-initialized is in its new L, or has no estimate, until it aligns again).
  std::vector<std::pair<std::int64_t, std::int64_t>> out_of_world_after_alignment() const;
  // Writes the files into `dir` (trajectories only when there is odometry, landmarks.csv only with landmarks in W).
  // Returns the files written.
  std::vector<std::filesystem::path> write(const std::filesystem::path& dir) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::int64_t, double> frame_wall_ms_, tracking_ms_, local_map_wall_ms_;
  std::map<std::int64_t, Eigen::Isometry3d> local_map_T_WB_;
  std::vector<std::pair<OdometryRecord, double>> odometry_;  // with end-to-end ms
  std::vector<RegistrationRecord> registrations_;
  std::vector<std::size_t> local_map_sizes_;
  std::map<std::uint64_t, LandmarkRecord> landmarks_W_;
  std::map<std::uint64_t, std::pair<std::int64_t, Eigen::Vector3d>> first_seen_;  // id -> keyframe stamp, p_LB
};

}  // namespace twinslam::cli
