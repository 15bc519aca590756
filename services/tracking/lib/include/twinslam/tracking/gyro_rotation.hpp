#pragma once
// The camera's rotation between two image stamps from the gyroscope: the KLT prediction of the frontend.
// Integration is common/imu's (Forster et al., TRO 2017, Sec. V-A: dR_ij = prod Exp((w_k - b_g) dt), midpoint rule,
// samples interpolated at the stamps), the same as the estimator's preintegration, so both agree on the rotation.
#include <cstdint>
#include <optional>
#include <span>

#include <Eigen/Core>

#include "twinslam/imu/imu_types.hpp"

namespace twinslam::tracking {

// R_prev_curr_C = R_CB R_BprevBcurr R_BC: maps camera coordinates at t_curr_ns to camera coordinates at t_prev_ns.
// `samples`: a time-sorted IMU buffer (strictly increasing stamps), possibly much longer than [t_prev, t_curr];
// R_BC: rotation of the camera in the body (IMU) frame (EuRoC T_BS); gyro_bias_B [rad/s] is subtracted.
// Returns nullopt when the buffer does not cover [t_prev_ns, t_curr_ns] (e.g. IMU not yet received) or
// t_curr_ns <= t_prev_ns; the caller then tracks without prediction. Throws InputError on non-finite samples.
std::optional<Eigen::Matrix3d> gyro_rotation_C(std::span<const imu::ImuSample> samples, std::int64_t t_prev_ns,
                                               std::int64_t t_curr_ns, const Eigen::Matrix3d& R_BC,
                                               const Eigen::Vector3d& gyro_bias_B = Eigen::Vector3d::Zero());

}  // namespace twinslam::tracking
