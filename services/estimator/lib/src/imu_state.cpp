#include "twinslam/estimator/imu_state.hpp"

#include <ceres/manifold.h>
#include <ceres/product_manifold.h>

namespace twinslam::estimator {

void pack(const ImuState& state, double* pose, double* speed_bias) {
  Eigen::Map<Eigen::Vector3d>{pose} = state.p_L;
  Eigen::Map<Eigen::Vector4d>{pose + 3} = state.q_LB.coeffs();  // x y z w
  Eigen::Map<Eigen::Vector3d>{speed_bias} = state.v_L;
  Eigen::Map<Eigen::Vector3d>{speed_bias + 3} = state.bias.gyro;
  Eigen::Map<Eigen::Vector3d>{speed_bias + 6} = state.bias.accel;
}

ImuState unpack(const double* pose, const double* speed_bias) {
  ImuState s;
  s.p_L = Eigen::Map<const Eigen::Vector3d>(pose);
  s.q_LB.coeffs() = Eigen::Map<const Eigen::Vector4d>(pose + 3);
  s.v_L = Eigen::Map<const Eigen::Vector3d>(speed_bias);
  s.bias.gyro = Eigen::Map<const Eigen::Vector3d>(speed_bias + 3);
  s.bias.accel = Eigen::Map<const Eigen::Vector3d>(speed_bias + 6);
  return s;
}

ceres::Manifold* new_pose_manifold() {
  return new ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>{};
}

}  // namespace twinslam::estimator
