#include "twinslam/sim/sim_camera.hpp"

#include <cmath>

#include "twinslam/sim/camera_calibration.hpp"
#include "twinslam/sim/scenario_io.hpp"

namespace twinslam::sim {

CameraConfig sim_camera_config(const Scenario& scenario) {
  const auto& c = scenario.camera;
  CameraConfig cfg;
  auto& k = cfg.intrinsics;
  k.width = c.width;
  k.height = c.height;
  k.cu = (c.width - 1) / 2.0;
  k.cv = (c.height - 1) / 2.0;
  const double half_fov = c.fov_deg * M_PI / 360.0;
  if (c.model == "fisheye-equidistant") {
    k.distortion = DistortionModel::kEquidistant;
    k.fu = k.fv = (c.width / 2.0) / half_fov;
    k.coefficients = {0, 0, 0, 0};
  } else {
    k.distortion = DistortionModel::kRadialTangential;
    k.fu = k.fv = (c.width / 2.0) / std::tan(half_fov);
    k.coefficients = {-0.05, 0.01, 0, 0};
  }
  cfg.T_BC = camera_T_BC(scenario);
  cfg.rate_hz = c.rate_hz;
  return cfg;
}

CameraConfig calibrated_sim_camera_config(const Scenario& scenario) {
  CameraConfig cfg = sim_camera_config(scenario);
  const CameraIntrinsicErrors e = camera_intrinsic_errors(scenario);
  auto& k = cfg.intrinsics;
  k.fu *= e.focal_scale;
  k.fv *= e.focal_scale;
  k.cu += e.principal_point_shift_px.x();
  k.cv += e.principal_point_shift_px.y();
  k.coefficients[0] += e.k1_offset;
  cfg.T_BC = calibrated_T_BC(scenario);
  return cfg;
}

}  // namespace twinslam::sim
