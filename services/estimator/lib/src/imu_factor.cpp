#include "twinslam/estimator/imu_factor.hpp"

#include <stdexcept>
#include <utility>

#include "twinslam/geometry/quaternion.hpp"

namespace twinslam::estimator {

ImuFactor::ImuFactor(std::shared_ptr<const Preintegration> preintegration, const Eigen::Vector3d& g_L)
    : pre_(std::move(preintegration)), g_L_(g_L) {
  if (!pre_) throw std::invalid_argument("ImuFactor: null preintegration");
}

bool ImuFactor::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const ImuState si = unpack(parameters[0], parameters[1]);
  const ImuState sj = unpack(parameters[2], parameters[3]);
  const bool want_jacobians = jacobians != nullptr;
  ImuResidualJacobians J;
  const Vector15d r = imu_residual(*pre_, si, sj, g_L_, want_jacobians ? &J : nullptr);

  const auto& S = pre_->sqrt_information();
  Eigen::Map<Vector15d>{residuals} = S.triangularView<Eigen::Lower>() * r;
  if (!want_jacobians) return true;

  using PoseJacobian = Eigen::Matrix<double, 15, kPoseSize, Eigen::RowMajor>;
  using SpeedBiasJacobian = Eigen::Matrix<double, 15, kSpeedBiasSize, Eigen::RowMajor>;
  auto pose_block = [&](double* out, const Eigen::Matrix<double, 15, 6>& local, const Eigen::Quaterniond& q) {
    Eigen::Map<PoseJacobian> Jp(out);
    Jp.leftCols<3>() = S.triangularView<Eigen::Lower>() * local.leftCols<3>();
    Jp.rightCols<4>() =
        S.triangularView<Eigen::Lower>() * (local.rightCols<3>() * geometry::right_perturbation_jacobian(q));
  };
  if (jacobians[0] != nullptr) pose_block(jacobians[0], J.pose_i, si.q_LB);
  if (jacobians[1] != nullptr) {
    Eigen::Map<SpeedBiasJacobian>{jacobians[1]} = S.triangularView<Eigen::Lower>() * J.speed_bias_i;
  }
  if (jacobians[2] != nullptr) pose_block(jacobians[2], J.pose_j, sj.q_LB);
  if (jacobians[3] != nullptr) {
    Eigen::Map<SpeedBiasJacobian>{jacobians[3]} = S.triangularView<Eigen::Lower>() * J.speed_bias_j;
  }
  return true;
}

}  // namespace twinslam::estimator
