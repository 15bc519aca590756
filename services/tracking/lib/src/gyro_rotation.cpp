#include "twinslam/tracking/gyro_rotation.hpp"

#include "twinslam/imu/imu_samples.hpp"

namespace twinslam::tracking {

std::optional<Eigen::Matrix3d> gyro_rotation_C(std::span<const imu::ImuSample> samples, std::int64_t t_prev_ns,
                                               std::int64_t t_curr_ns, const Eigen::Matrix3d& R_BC,
                                               const Eigen::Vector3d& gyro_bias_B) {
  const auto R_BprevBcurr = imu::gyro_rotation_B(samples, t_prev_ns, t_curr_ns, gyro_bias_B);
  if (!R_BprevBcurr) return std::nullopt;
  // Conjugate by the fixed camera mounting: R_CprevCcurr = R_CB R_BprevBcurr R_BC.
  return R_BC.transpose() * *R_BprevBcurr * R_BC;
}

}  // namespace twinslam::tracking
