#pragma once
// A restarted estimator resumes from its own checkpoint (issue 14: the estimator killed and restarted in flight).
// A new process has no history: at rest it initializes statically, in motion only when the flight accelerates enough
// to give metric scale (motion_init.hpp) - in a constant-rate turn the centripetal acceleration is constant in body
// axes like an accelerometer bias, and it never does. The running estimator therefore writes, once per
// checkpoint interval, the newest state in W (pose, velocity, IMU biases) to a small JSON file on its own host; the
// new process starts its window from that state carried over the gap (constant velocity; the sigmas grow with
// bounds on acceleration and turn rate over the gap) and its T_WL from that pose, as `--initial-pose` does.
// Checkpoints older than max_age_s by the data's own clock are not used. Pure library, no DDS.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "twinslam/estimator/global_fusion.hpp"
#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/state_prior.hpp"

namespace twinslam::estimator {

struct EstimatorCheckpoint {
  std::int64_t stamp_ns = 0;                                 // sensor time of the state
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             // position of B in W [m]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  // orientation of B in W
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             // velocity of B in W [m/s]
  ImuBias bias;                                              // b_g [rad/s], b_a [m/s^2] in B
  double position_sigma_m = 0.5;                             // 1-sigma of p_W per axis at stamp_ns [m]
  double yaw_sigma_deg = 1.0;                                // 1-sigma of the heading at stamp_ns [deg]
};

struct ResumeConfig {
  double max_age_s = 5.0;        // a checkpoint older than this at the first frame is not used [s]
  double max_accel_mps2 = 1.0;   // bound on the acceleration during the gap: velocity and position sigmas [m/s^2]
  double max_rate_degps = 10.0;  // bound on the turn rate during the gap: attitude and heading sigmas [deg/s]
  double velocity_sigma_mps = 0.1;  // of the checkpoint's velocity itself [m/s]
  double tilt_sigma_deg = 0.5;      // of its roll / pitch [deg]
  double gyro_bias_sigma_radps = 0.002;  // of its gyro bias (estimated in flight) [rad/s]
  double accel_bias_sigma_mps2 = 0.05;   // of its accelerometer bias [m/s^2]
  void validate() const;            // throws InputError naming the field
};

// The window's initial state and the pose that sets T_WL, for the first frame at frame_ns.
struct ResumePlan {
  ImuState state_L;          // in the new L: gravity-aligned, heading 0, origin at the body (as after an init)
  StatePriorSigmas sigmas;   // its prior
  InitialPose pose_W;        // the body's position and heading in W at frame_ns, with sigmas
  double age_s = 0.0;        // frame_ns - checkpoint stamp [s]
};

// nullopt when the checkpoint is from the future or older than max_age_s at frame_ns (the reason in *why).
std::optional<ResumePlan> plan_resume(const EstimatorCheckpoint& checkpoint, std::int64_t frame_ns,
                                      const ResumeConfig& config, std::string* why = nullptr);

// Writes the checkpoint atomically (a temporary file renamed over `path`); throws std::runtime_error on failure.
void write_checkpoint(const std::filesystem::path& path, const EstimatorCheckpoint& checkpoint);
// Reads a checkpoint; nullopt when `path` does not exist; InputError naming the file and the key when it is not one.
std::optional<EstimatorCheckpoint> read_checkpoint(const std::filesystem::path& path);

}  // namespace twinslam::estimator
