#pragma once
// Navigation state of one keyframe and its layout in Ceres parameter blocks.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/estimator/imu_types.hpp"

namespace ceres {
class Manifold;
}

namespace twinslam::estimator {

// State of body B at a keyframe, in the estimator's gravity-aligned local frame L.
struct ImuState {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();                // position of B in L [m] (translation of T_LB)
  Eigen::Quaterniond q_LB = Eigen::Quaterniond::Identity();     // orientation of B in L (rotation of T_LB)
  Eigen::Vector3d v_L = Eigen::Vector3d::Zero();                // velocity of B in L [m/s]
  ImuBias bias;                                                 // b_g [rad/s], b_a [m/s^2] in B
};

// Parameter blocks per keyframe:
//   pose       = [p_L x y z, q_LB x y z w]  (7 ambient, 6 tangent: ceres::ProductManifold of EuclideanManifold<3>
//                                            and EigenQuaternionManifold, see new_pose_manifold())
//   speed_bias = [v_L x y z, b_g x y z, b_a x y z]  (9, Euclidean)
// Velocity and biases share a block because every factor that touches one (IMU factor, priors, marginalization)
// touches all three; it halves the number of blocks Ceres orders.
inline constexpr int kPoseSize = 7;
inline constexpr int kPoseTangentSize = 6;
inline constexpr int kSpeedBiasSize = 9;

void pack(const ImuState& state, double* pose, double* speed_bias);
ImuState unpack(const double* pose, const double* speed_bias);

// The manifold of the pose block. The caller owns the result (ceres::Problem takes ownership when given it, unless
// Problem::Options::manifold_ownership says otherwise).
ceres::Manifold* new_pose_manifold();

}  // namespace twinslam::estimator
