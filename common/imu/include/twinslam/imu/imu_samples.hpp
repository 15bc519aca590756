#pragma once
// Helpers on a time-sorted IMU buffer, shared by the tracking frontend and the estimator so that both integrate the
// gyroscope the same way: the covering slice of an interval, the integration nodes (samples interpolated at the
// interval's stamps), and the gyro rotation between two stamps.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "twinslam/imu/imu_types.hpp"

namespace twinslam::imu {

// The part of a time-sorted IMU buffer needed for [t_i_ns, t_j_ns]: from the last sample at or before t_i_ns to the
// first sample at or after t_j_ns (clipped to the buffer, so coverage must still be checked). Binary search, so a
// service can keep one long buffer and pass the slice.
std::span<const ImuSample> covering_samples(std::span<const ImuSample> sorted, std::int64_t t_i_ns,
                                            std::int64_t t_j_ns);

// Linear interpolation of two samples at stamp t (a.stamp_ns <= t <= b.stamp_ns).
ImuSample interpolate(const ImuSample& a, const ImuSample& b, std::int64_t t);

// The integration nodes of [t_i_ns, t_j_ns]: the sample interpolated at t_i, every sample strictly inside, the sample
// interpolated at t_j. `samples` must have strictly increasing stamps, finite values and cover the interval; throws
// twinslam::InputError naming the stamp otherwise (and for t_j_ns <= t_i_ns).
std::vector<ImuSample> integration_nodes(std::span<const ImuSample> samples, std::int64_t t_i_ns, std::int64_t t_j_ns);

// dR = prod_k Exp((w_mid_k - b_g) h_k) over the nodes, w_mid the mean of two consecutive gyro readings (the midpoint
// rule of the estimator's preintegration, Forster et al., TRO 2017, Sec. V-A), projected onto SO(3) once at the end.
// Maps B at the last node into B at the first: R_BiBj.
Eigen::Matrix3d integrate_gyro(const std::vector<ImuSample>& nodes, const Eigen::Vector3d& gyro_bias_B);

// R_BiBj between two stamps from a long buffer; nullopt when the buffer does not cover [t_i_ns, t_j_ns] or
// t_j_ns <= t_i_ns. Throws InputError on non-finite or unordered samples in the covering slice.
std::optional<Eigen::Matrix3d> gyro_rotation_B(std::span<const ImuSample> buffer, std::int64_t t_i_ns,
                                               std::int64_t t_j_ns, const Eigen::Vector3d& gyro_bias_B);

}  // namespace twinslam::imu
