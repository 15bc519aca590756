// The scale prior of 7-DoF ICP (icp.hpp ScalePrior): a tight prior holds the scale where it says (and the keyframe
// then where that scale puts it), a loose one leaves the fit alone.
#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_twin.hpp"
#include "twinslam/registration/registration.hpp"

namespace twinslam::registration {
namespace {

const Eigen::Vector3d kBody = test::kCentre + Eigen::Vector3d(0.0, -5.0, 15.0);
const Eigen::Isometry3d kError = test::offset_about(kBody, {0.3, -0.2, 1.0}, 2.0, {0.5, -0.4, 0.3});

const TwinTileIndex& twin() {
  static const TwinTileIndex index = test::make_index(test::sample_grid(test::city_surfaces(), 0.5));
  return index;
}

RegistrationConfig seven_dof() {
  RegistrationConfig c;
  c.voxel_size_m = 0.0;
  c.estimate_scale = true;
  return c;
}

// Landmarks of the city scaled by `scale` about the keyframe (the VIO window's scale error).
SourceInput scaled_cloud(double scale) {
  std::vector<Eigen::Vector3d> p = test::sample_noisy(test::city_surfaces(), 3000, 0.1, 21);
  for (auto& x : p) x = kBody + scale * (x - kBody);
  return test::make_source(p, kError, kBody);
}

double keyframe_error_m(const RegistrationResult& r) { return (r.correction_W * (kError * kBody) - kBody).norm(); }

TEST(RegistrationScalePrior, ATightPriorHoldsTheScaleALooseOneLeavesTheFitAlone) {
  const SourceInput in = scaled_cloud(1.03);
  const RegistrationResult free = register_cloud(seven_dof(), twin(), in);
  ASSERT_TRUE(free.accepted()) << free.reason;
  EXPECT_NEAR(free.scale, 1.0 / 1.03, 0.002);  // ICP scales the cloud back onto the twin
  const RegistrationResult loose = register_cloud(seven_dof(), twin(), in, std::nullopt, ScalePrior{0.0, 1.0});
  EXPECT_NEAR(loose.scale, free.scale, 1e-4);
  const RegistrationResult held = register_cloud(seven_dof(), twin(), in, std::nullopt, ScalePrior{0.0, 1e-5});
  EXPECT_NEAR(held.scale, 1.0, 1e-4);
  EXPECT_GT(keyframe_error_m(held), 10.0 * keyframe_error_m(free));  // held at the wrong scale: rigid ICP's bias
  const RegistrationResult right =
      register_cloud(seven_dof(), twin(), in, std::nullopt, ScalePrior{std::log(1.0 / 1.03), 1e-3});
  EXPECT_NEAR(right.scale, 1.0 / 1.03, 0.001);
  EXPECT_LT(keyframe_error_m(right), 0.03);
}

}  // namespace
}  // namespace twinslam::registration
