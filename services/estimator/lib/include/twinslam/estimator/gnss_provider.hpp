#pragma once
// GNSS position fixes as terms of the sliding window (issue 13, modes vio-gnss and vio-twin-gnss; the paper's
// SVO-GPS baseline): a fix z_W at time t, attached to the keyframe nearest in time (|t - t_k| <= max_dt_s), predicts
// the antenna from that keyframe's state by its velocity over dt = t - t_k, through T_WL:
//   r = S ( Rz(yaw_WL) (p_LB + v_L dt + R_LB l_B) + p_WL - z_W ),   S^T S = C^-1 (C: the fix's covariance in W)
// with l_B the antenna lever arm in B. Blocks: pose [7], speed/bias [9], T_WL [4]; residual 3 (E, N, U); Huber loss.
// Constant velocity over dt (at most max_dt_s, 0.5 s: 12 cm at 1 m/s^2) stands in for the
// preintegrated IMU, far below GNSS noise. Fixes that find no keyframe within max_dt_s before the window moves past
// them are counted (unmatched), never dropped silently; a fix on a marginalized keyframe lives on in the prior.
#include <cstdint>
#include <map>
#include <memory>

#include <Eigen/Core>

#include "twinslam/estimator/window_factor_provider.hpp"

namespace ceres {
class CostFunction;
class LossFunction;
}  // namespace ceres

namespace twinslam::estimator {

struct GnssProviderConfig {
  Eigen::Vector3d lever_arm_B = Eigen::Vector3d::Zero();  // antenna in the body frame [m]
  double huber_delta = 3.0;   // robust loss on the whitened 3-residual [1]
  double max_dt_s = 0.5;      // a fix attaches to a keyframe at most this far in time [s]
  void validate() const;      // throws twinslam::InputError naming the field
};

struct GnssProviderCounts {
  unsigned long long received = 0, attached = 0, unmatched = 0, marginalized = 0;
};

// The cost function alone (for tests and other providers). Caller owns the result.
ceres::CostFunction* new_gnss_position_factor(const Eigen::Vector3d& z_W, const Eigen::Matrix3d& cov_W, double dt_s,
                                              const Eigen::Vector3d& lever_arm_B);

class GnssProvider final : public WindowFactorProvider {
 public:
  explicit GnssProvider(const GnssProviderConfig& config = {});

  // A fix at stamp_ns: z_W [m, W] with covariance cov_W [m^2] (symmetric positive definite; else InputError).
  void add_fix(std::int64_t stamp_ns, const Eigen::Vector3d& z_W, const Eigen::Matrix3d& cov_W);
  // Terms are added only while active (T_WL has a value: after the alignment).
  void set_active(bool active) { active_ = active; }

  void add_terms(const WindowBlocks& blocks, std::vector<ResidualTerm>& terms) override;
  void keyframe_marginalized(std::int64_t stamp_ns) override;

  const GnssProviderCounts& counts() const { return counts_; }

 private:
  struct Fix {
    Eigen::Vector3d z_W;
    Eigen::Matrix3d cov_W;
    std::int64_t attached_to = -1;              // keyframe stamp while attached
    std::shared_ptr<ceres::CostFunction> cost;  // for that keyframe (dt fixed by it)
  };

  GnssProviderConfig config_;
  std::shared_ptr<ceres::LossFunction> loss_;
  std::map<std::int64_t, Fix> fixes_;  // by fix stamp
  bool active_ = false;
  GnssProviderCounts counts_;
};

}  // namespace twinslam::estimator
