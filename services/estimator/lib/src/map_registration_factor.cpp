#include "twinslam/estimator/map_registration_factor.hpp"

#include <algorithm>

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>
#include <Eigen/Eigenvalues>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/world_alignment.hpp"

namespace twinslam::estimator {
namespace {

struct MapRegistrationResidual {
  Eigen::Quaterniond q_meas_inv;  // R_WB_meas^T
  Eigen::Vector3d p_meas;
  Eigen::Matrix<double, 6, 6> S;

  template <class T>
  bool operator()(const T* pose, const T* T_WL, T* r) const {
    // R_WB(x) = Rz(yaw) R_LB, as quaternions (Eigen order in the pose block: x, y, z, w).
    const Eigen::Quaternion<T> q_LB(pose[6], pose[3], pose[4], pose[5]);
    const Eigen::Quaternion<T> q_z(Eigen::AngleAxis<T>(T_WL[3], Eigen::Matrix<T, 3, 1>::UnitZ()));
    const Eigen::Quaternion<T> q_err = q_z * q_LB * q_meas_inv.cast<T>();
    const T q_wxyz[4] = {q_err.w(), q_err.x(), q_err.y(), q_err.z()};
    Eigen::Matrix<T, 6, 1> e;
    ceres::QuaternionToAngleAxis(q_wxyz, e.data());  // Log, world frame (left error)
    T p_W[3];
    world_from_local(T_WL, pose, p_W);
    for (int k = 0; k < 3; ++k) e[3 + k] = p_W[k] - T(p_meas[k]);
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residual(r);
    residual = S.cast<T>() * e;
    return true;
  }
};

}  // namespace

Eigen::Isometry3d MapRegistration::measured_T_WB() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = dR_W * T_WB_estimate.linear();
  T.translation() = T_WB_estimate.translation() + dp_W;
  return T;
}

MapRegistration map_registration_from_correction(std::int64_t keyframe_stamp_ns, const Eigen::Isometry3d& T_WB_estimate,
                                                 const Eigen::Isometry3d& dT_W,
                                                 const Eigen::Matrix<double, 6, 6>& information) {
  MapRegistration m;
  m.keyframe_stamp_ns = keyframe_stamp_ns;
  m.T_WB_estimate = T_WB_estimate;
  m.dR_W = dT_W.linear();
  const Eigen::Vector3d c = T_WB_estimate.translation();
  m.dp_W = dT_W * c - c;
  m.information = information;
  return m;
}

std::string registration_problem(const Eigen::Isometry3d& dT_W, const Eigen::Matrix<double, 6, 6>& information) {
  if (!dT_W.matrix().allFinite()) return "correction not finite";
  const Eigen::Matrix3d R = dT_W.linear();
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0.0) {
    return "correction rotation not a rotation";
  }
  if (!information.allFinite()) return "information not finite";
  const double scale = information.cwiseAbs().maxCoeff();
  if ((information - information.transpose()).cwiseAbs().maxCoeff() > 1e-6 * scale) return "information not symmetric";
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(information);
  if (es.eigenvalues().minCoeff() < -1e-9 * std::max(scale, 1e-300)) return "information not positive semi-definite";
  return "";
}

Eigen::Matrix<double, 6, 6> information_square_root(const Eigen::Matrix<double, 6, 6>& H) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(0.5 * (H + H.transpose()));
  const Eigen::Matrix<double, 6, 1> s = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return s.asDiagonal() * es.eigenvectors().transpose();
}

ceres::CostFunction* new_map_registration_factor(const MapRegistration& m) {
  const Eigen::Isometry3d T = m.measured_T_WB();
  auto* f = new MapRegistrationResidual{Eigen::Quaterniond(T.linear()).conjugate(), T.translation(),
                                        information_square_root(m.information)};
  return new ceres::AutoDiffCostFunction<MapRegistrationResidual, 6, kPoseSize, kWorldAlignmentSize>(f);
}

Eigen::Matrix<double, 6, 6> to_registration_order(const Eigen::Matrix<double, 6, 6>& cov_pW_thetaB,
                                                  const Eigen::Matrix3d& R_WB) {
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();  // (dtheta_W, dp_W) = J (dp_W, dtheta_B)
  J.block<3, 3>(0, 3) = R_WB;
  J.block<3, 3>(3, 0) = Eigen::Matrix3d::Identity();
  const Eigen::Matrix<double, 6, 6> out = J * cov_pW_thetaB * J.transpose();
  return 0.5 * (out + out.transpose());
}

}  // namespace twinslam::estimator
