#include "twinslam/tracking/gyro_rotation.hpp"

#include "twinslam/estimator/preintegration.hpp"

namespace twinslam::tracking {

std::optional<Eigen::Matrix3d> gyro_rotation_C(std::span<const estimator::ImuSample> samples, std::int64_t t_prev_ns,
                                               std::int64_t t_curr_ns, const Eigen::Matrix3d& R_BC,
                                               const Eigen::Vector3d& gyro_bias_B) {
  if (t_curr_ns <= t_prev_ns || samples.empty()) return std::nullopt;
  const auto slice = estimator::covering_samples(samples, t_prev_ns, t_curr_ns);
  if (slice.empty() || slice.front().stamp_ns > t_prev_ns || slice.back().stamp_ns < t_curr_ns) return std::nullopt;
  estimator::ImuBias bias;
  bias.gyro = gyro_bias_B;
  const estimator::Preintegration pre(estimator::PreintegrationConfig{}, bias, slice, t_prev_ns, t_curr_ns);
  // dR = R_LBprev^T R_LBcurr = R_BprevBcurr; conjugate by the fixed camera mounting.
  return R_BC.transpose() * pre.delta().R * R_BC;
}

}  // namespace twinslam::tracking
