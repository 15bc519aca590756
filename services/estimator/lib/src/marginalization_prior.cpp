// The prior factor left by marginalization: r = r0 + J0 (x [-] x0) on the kept blocks.
#include <stdexcept>
#include <utility>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/marginalization.hpp"
#include "twinslam/geometry/quaternion.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {

Eigen::Matrix<double, 4, 3> quaternion_right_lift(const Eigen::Quaterniond& q) {
  // q (x) (0, dtheta / 2): vector part (w I + [v]x) dtheta / 2, scalar part -v . dtheta / 2.
  Eigen::Matrix<double, 4, 3> L;
  L.topRows<3>() = q.w() * Eigen::Matrix3d::Identity() + geometry::skew(q.vec());
  L.row(3) = -q.vec().transpose();
  return 0.5 * L;
}

MarginalizationPrior::MarginalizationPrior(std::vector<double*> blocks, std::vector<BlockKind> kinds,
                                           std::vector<int> sizes, Eigen::MatrixXd J0, Eigen::VectorXd r0)
    : blocks_(std::move(blocks)), kinds_(std::move(kinds)), J0_(std::move(J0)), r0_(std::move(r0)) {
  if (blocks_.size() != kinds_.size() || blocks_.size() != sizes.size() || J0_.rows() != r0_.size()) {
    throw std::invalid_argument("MarginalizationPrior: inconsistent sizes");
  }
  int offset = 0;
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    offsets_.push_back(offset);
    offset += kinds_[k] == BlockKind::kPose ? kPoseTangentSize : sizes[k];
    x0_.emplace_back(Eigen::Map<const Eigen::VectorXd>(blocks_[k], sizes[k]));  // the linearization point
    mutable_parameter_block_sizes()->push_back(sizes[k]);
  }
  if (offset != J0_.cols()) throw std::invalid_argument("MarginalizationPrior: J0 does not match the blocks");
  set_num_residuals(static_cast<int>(J0_.rows()));
}

bool MarginalizationPrior::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  Eigen::VectorXd dx(J0_.cols());
  std::vector<Eigen::Vector3d> theta(blocks_.size());
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const int n = static_cast<int>(x0_[k].size());
    const Eigen::Map<const Eigen::VectorXd> x(parameters[k], n);
    if (kinds_[k] == BlockKind::kEuclidean) {
      dx.segment(offsets_[k], n) = x - x0_[k];
      continue;
    }
    const Eigen::Quaterniond q0(Eigen::Map<const Eigen::Quaterniond>(x0_[k].data() + 3));
    const Eigen::Quaterniond q(Eigen::Map<const Eigen::Quaterniond>(parameters[k] + 3));
    theta[k] = geometry::quaternion_log(q0.normalized().conjugate() * q.normalized());  // q = q0 Exp(theta)
    dx.segment<3>(offsets_[k]) = x.head<3>() - x0_[k].head<3>();
    dx.segment<3>(offsets_[k] + 3) = theta[k];
  }
  Eigen::Map<Eigen::VectorXd>(residuals, J0_.rows()) = r0_ + J0_ * dx;
  if (jacobians == nullptr) return true;

  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    if (jacobians[k] == nullptr) continue;
    const int n = static_cast<int>(x0_[k].size());
    Eigen::Map<RowMajor> J(jacobians[k], J0_.rows(), n);
    if (kinds_[k] == BlockKind::kEuclidean) {
      J = J0_.middleCols(offsets_[k], n);
      continue;
    }
    // d Log(q0^-1 q) / dq: Log(Exp(theta) Exp(delta)) ~= theta + Jr^-1(theta) delta (Forster Sec. II), and
    // delta = right_perturbation_jacobian(q) dq.
    const Eigen::Quaterniond q(Eigen::Map<const Eigen::Quaterniond>(parameters[k] + 3));
    J.leftCols(3) = J0_.middleCols(offsets_[k], 3);
    J.rightCols(4) = J0_.middleCols(offsets_[k] + 3, 3) * geometry::so3_right_jacobian_inverse(theta[k]) *
                     geometry::right_perturbation_jacobian(q);
  }
  return true;
}

}  // namespace twinslam::estimator
