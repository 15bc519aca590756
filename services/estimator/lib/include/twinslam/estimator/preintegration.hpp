#pragma once
// On-manifold IMU preintegration between two keyframes (Forster, Carlone, Dellaert, Scaramuzza, "On-Manifold
// Preintegration for Real-Time Visual-Inertial Odometry", IEEE TRO 33(1), 2017; "Forster" below).
//
// Given IMU samples and keyframe stamps t_i < t_j, computes the preintegrated measurements (Forster Sec. V-A)
//   dR_ij = prod_k Exp((w_k - b_g) dt),  dv_ij = sum_k dR_ik (a_k - b_a) dt,  dp_ij = sum_k dv_ik dt + 1/2 dR_ik a dt^2
// at a linearization bias b_bar, their 9x9 covariance (Forster Sec. V-B, App. A, in the order [dphi, dv, dp]) and their
// Jacobians w.r.t. the bias (Forster Sec. V-C, App. B) for the first-order bias update of Forster eq. 44.
// The samples at t_i and t_j are linearly interpolated, so keyframe stamps need not fall on IMU stamps.
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "twinslam/estimator/imu_types.hpp"
#include "twinslam/imu/imu_samples.hpp"

namespace twinslam::estimator {

enum class ImuIntegration {
  kEuler,     // zero-order hold of the earlier sample, as in Forster's discretization (first-order accurate)
  kMidpoint,  // mean gyro over the interval, trapezoid of the rotated accelerations (second-order accurate)
};

// Configuration of the preintegration module (one struct, validated in validate()).
struct PreintegrationConfig {
  ImuNoise noise;
  ImuIntegration integration = ImuIntegration::kMidpoint;
  // The first-order bias update (Forster eq. 44) is only accurate near the linearization bias; beyond these offsets
  // repropagate_if_needed() integrates the samples again at the new bias.
  double repropagate_gyro_bias = 0.01;   // |b_g - b_g_bar| [rad/s]
  double repropagate_accel_bias = 0.1;   // |b_a - b_a_bar| [m/s^2]
  // An IMU gap (a dropped driver buffer, a cable fault: issue 15): a step between samples longer than gap_s is
  // integrated from the interpolated readings, but the motion inside it was not measured. Its covariance then adds
  // an unknown constant deviation of the rate and the acceleration from that interpolation (sigmas below), so the
  // IMU factor across the gap weighs as little as what is known of it and vision carries the window.
  double gap_s = 0.05;                   // [s] (4 samples at 200 Hz; 10 at 200 Hz with 2 dropped are not a gap)
  double gap_gyro_sigma = 0.5;           // unmeasured rate during a gap [rad/s]
  double gap_accel_sigma = 3.0;          // unmeasured acceleration during a gap [m/s^2]

  void validate() const;  // throws twinslam::InputError naming the bad field
};

// Bias-corrected preintegrated measurements.
struct PreintegratedDelta {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // dR_ij = R_LBi^T R_LBj (without gravity)
  Eigen::Vector3d v = Eigen::Vector3d::Zero();      // dv_ij in B_i [m/s]
  Eigen::Vector3d p = Eigen::Vector3d::Zero();      // dp_ij in B_i [m]
};

// Jacobians of the preintegrated measurements w.r.t. the bias at the linearization point (Forster App. B);
// dR_dbg acts on the right: dR(b_bar + db) ~= dR(b_bar) Exp(dR_dbg db_g).
struct PreintegrationBiasJacobians {
  Eigen::Matrix3d dR_dbg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dv_dbg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dv_dba = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dp_dbg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dp_dba = Eigen::Matrix3d::Zero();
};

// The slice of a long IMU buffer that Preintegration needs (common/imu).
using imu::covering_samples;

class Preintegration {
 public:
  using Matrix9d = Eigen::Matrix<double, 9, 9>;
  using Matrix15d = Eigen::Matrix<double, 15, 15>;

  // Integrates over [t_i_ns, t_j_ns]. `samples` must have strictly increasing stamps, finite values, and cover the
  // interval (first stamp <= t_i_ns, last stamp >= t_j_ns); samples outside it are ignored but still validated, so pass
  // covering_samples() of a long buffer. Throws twinslam::InputError otherwise (and for t_j_ns <= t_i_ns or an invalid
  // config).
  Preintegration(const PreintegrationConfig& config, const ImuBias& linearization_bias,
                 std::span<const ImuSample> samples, std::int64_t t_i_ns, std::int64_t t_j_ns);

  // Integrates the stored samples again at a new linearization bias.
  void repropagate(const ImuBias& linearization_bias);
  // Repropagates when `bias` is farther from the linearization bias than the config thresholds; returns true if so.
  bool repropagate_if_needed(const ImuBias& bias);

  // Measurements at the linearization bias, and corrected to `bias` to first order (Forster eq. 44).
  const PreintegratedDelta& delta() const { return delta_; }
  PreintegratedDelta corrected(const ImuBias& bias) const;

  const PreintegrationBiasJacobians& bias_jacobians() const { return jac_; }
  const ImuBias& linearization_bias() const { return bias_bar_; }
  // Covariance of [dphi, dv, dp] (rad, m/s, m).
  const Matrix9d& covariance() const { return cov_; }
  // Covariance of the 15-dim IMU factor residual [dphi, dv, dp, b_g random walk, b_a random walk]: the preintegration
  // block plus the bias random walk over t_j - t_i (Forster Sec. V-D), block diagonal.
  Matrix15d residual_covariance() const;
  // Lower-triangular S with S^T S = residual_covariance()^-1: the IMU factor whitens its residual as S r.
  const Matrix15d& sqrt_information() const { return sqrt_info_; }

  std::int64_t t_i_ns() const { return t_i_ns_; }
  std::int64_t t_j_ns() const { return t_j_ns_; }
  double dt() const { return dt_; }  // t_j - t_i [s]
  double longest_gap_s() const { return longest_gap_s_; }  // longest step between nodes [s]
  const PreintegrationConfig& config() const { return config_; }
  // The integration nodes: the interpolated boundary samples and the samples strictly between them.
  const std::vector<ImuSample>& nodes() const { return nodes_; }

 private:
  void propagate();
  void step(const ImuSample& a, const ImuSample& b);

  PreintegrationConfig config_;
  ImuBias bias_bar_;
  std::vector<ImuSample> nodes_;
  std::int64_t t_i_ns_ = 0;
  std::int64_t t_j_ns_ = 0;
  double dt_ = 0.0;
  double longest_gap_s_ = 0.0;

  PreintegratedDelta delta_;
  PreintegrationBiasJacobians jac_;
  Matrix9d cov_ = Matrix9d::Zero();
  Matrix15d sqrt_info_ = Matrix15d::Zero();
};

}  // namespace twinslam::estimator
