#include "twinslam/estimator/world_alignment.hpp"

#include <cmath>

#include <ceres/sized_cost_function.h>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {
namespace {

double wrap_pi(double a) { return std::atan2(std::sin(a), std::cos(a)); }

class WorldAlignmentPrior final : public ceres::SizedCostFunction<4, kWorldAlignmentSize> {
 public:
  WorldAlignmentPrior(const Eigen::Isometry3d& T_WL0, const WorldAlignmentSigmas& s)
      : p0_(T_WL0.translation()), yaw0_(std::atan2(T_WL0.linear()(1, 0), T_WL0.linear()(0, 0))),
        inv_p_(1.0 / s.position_m), inv_yaw_(1.0 / s.yaw_rad) {}

  bool Evaluate(double const* const* x, double* r, double** J) const override {
    for (int k = 0; k < 3; ++k) r[k] = (x[0][k] - p0_[k]) * inv_p_;
    r[3] = wrap_pi(x[0][3] - yaw0_) * inv_yaw_;
    if (J != nullptr && J[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> j(J[0]);
      j.setZero();
      j.diagonal() << inv_p_, inv_p_, inv_p_, inv_yaw_;
    }
    return true;
  }

 private:
  Eigen::Vector3d p0_;
  double yaw0_, inv_p_, inv_yaw_;
};

}  // namespace

Eigen::Isometry3d world_alignment_pose(const double* b) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(b[3], Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() << b[0], b[1], b[2];
  return T;
}

void set_world_alignment_block(const Eigen::Isometry3d& T_WL, double* b) {
  b[0] = T_WL.translation().x();
  b[1] = T_WL.translation().y();
  b[2] = T_WL.translation().z();
  b[3] = std::atan2(T_WL.linear()(1, 0), T_WL.linear()(0, 0));
}

void WorldAlignmentSigmas::validate() const {
  if (!std::isfinite(position_m) || position_m <= 0.0 || !std::isfinite(yaw_rad) || yaw_rad <= 0.0) {
    throw InputError("world alignment prior: position_m and yaw_rad must be finite and > 0");
  }
}

ceres::CostFunction* new_world_alignment_prior(const Eigen::Isometry3d& T_WL0, const WorldAlignmentSigmas& sigmas) {
  sigmas.validate();
  return new WorldAlignmentPrior(T_WL0, sigmas);
}

}  // namespace twinslam::estimator
