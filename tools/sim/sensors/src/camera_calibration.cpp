#include "twinslam/sim/camera_calibration.hpp"

#include <cmath>
#include <random>

#include "seeds.hpp"
#include "twinslam/sim/scenario_io.hpp"

namespace twinslam::sim {

namespace {
Eigen::Vector3d unit_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  for (;;) {  // isotropic: a normalized 3-D normal draw
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = normal(rng);
    if (v.norm() > 1e-6) return v.normalized();
  }
}
}  // namespace

Eigen::Isometry3d calibrated_T_BC(const Scenario& scenario) {
  const Eigen::Isometry3d T_true = camera_T_BC(scenario);
  std::mt19937_64 rng = detail::make_rng(scenario.seed, detail::Stream::CameraExtrinsics);
  const Eigen::Vector3d axis = unit_direction(rng), direction = unit_direction(rng);  // both always drawn
  Eigen::Isometry3d T = T_true;
  const double angle = scenario.camera.extrinsic_error_deg * M_PI / 180.0;  // [rad]
  if (angle > 0) T.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * T_true.linear();
  if (scenario.camera.extrinsic_error_m > 0)
    T.translation() = T_true.translation() + scenario.camera.extrinsic_error_m * direction;
  return T;
}

}  // namespace twinslam::sim
