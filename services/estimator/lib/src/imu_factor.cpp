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

  // The residual covariance is block diagonal (9x9 preintegration block, then the diagonal bias random walk), so
  // S = [S9 0; 0 D] with S9 lower triangular and D diagonal; whitening by blocks avoids a dense 15x15 product.
  const auto& S = pre_->sqrt_information();
  const auto S9 = S.topLeftCorner<9, 9>();
  const auto D = S.bottomRightCorner<6, 6>().diagonal().asDiagonal();
  Eigen::Map<Vector15d> res{residuals};
  res.head<9>() = S9.lazyProduct(r.head<9>());
  res.tail<6>() = D * r.tail<6>();
  if (!want_jacobians) return true;

  auto whiten = [&](const auto& local, auto&& out) {
    out.template topRows<9>() = S9.lazyProduct(local.template topRows<9>());
    out.template bottomRows<6>() = D * local.template bottomRows<6>();
  };
  using PoseJacobian = Eigen::Matrix<double, 15, kPoseSize, Eigen::RowMajor>;
  using SpeedBiasJacobian = Eigen::Matrix<double, 15, kSpeedBiasSize, Eigen::RowMajor>;
  auto pose_block = [&](double* out, const Eigen::Matrix<double, 15, 6>& local, const Eigen::Quaterniond& q) {
    Eigen::Matrix<double, 15, kPoseSize> ambient;
    ambient.leftCols<3>() = local.leftCols<3>();
    ambient.rightCols<4>() = local.rightCols<3>() * geometry::right_perturbation_jacobian(q);
    whiten(ambient, Eigen::Map<PoseJacobian>{out});
  };
  if (jacobians[0] != nullptr) pose_block(jacobians[0], J.pose_i, si.q_LB);
  if (jacobians[1] != nullptr) whiten(J.speed_bias_i, Eigen::Map<SpeedBiasJacobian>{jacobians[1]});
  if (jacobians[2] != nullptr) pose_block(jacobians[2], J.pose_j, sj.q_LB);
  if (jacobians[3] != nullptr) whiten(J.speed_bias_j, Eigen::Map<SpeedBiasJacobian>{jacobians[3]});
  return true;
}

}  // namespace twinslam::estimator
