#pragma once
// Shared by the sim_world tests and bench/sim_render: cameras of the scenario defaults and a look-at pose.
#include <cmath>
#include <memory>

#include <Eigen/Geometry>

#include "twinslam/camera/camera_model.hpp"

namespace twinslam::sim::testing {

// 120 deg fisheye, 640 x 400: fu = fv = 320 px / (60 deg in rad), no distortion.
inline std::unique_ptr<CameraModel> fisheye_120() {
  CameraIntrinsics k;
  k.distortion = DistortionModel::kEquidistant;
  k.width = 640;
  k.height = 400;
  k.fu = k.fv = 320.0 / (M_PI / 3.0);
  k.cu = 319.5;
  k.cv = 199.5;
  return make_camera(k);
}

// 90 deg horizontal pinhole, 640 x 400, mild radial-tangential distortion.
inline std::unique_ptr<CameraModel> pinhole_90() {
  CameraIntrinsics k;
  k.distortion = DistortionModel::kRadialTangential;
  k.width = 640;
  k.height = 400;
  k.fu = k.fv = 320.0;
  k.cu = 319.5;
  k.cv = 199.5;
  k.coefficients = {-0.05, 0.01, 0.0005, -0.0003};
  return make_camera(k);
}

// T_WC of a camera at c_W looking at target_W (C: x right, y down, z forward; W: z up).
inline Eigen::Isometry3d look_at(const Eigen::Vector3d& c_W, const Eigen::Vector3d& target_W) {
  const Eigen::Vector3d z = (target_W - c_W).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() << x, y, z;
  T_WC.translation() = c_W;
  return T_WC;
}

}  // namespace twinslam::sim::testing
