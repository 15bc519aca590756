// Online calibration in the sliding window: the camera mounting (R_BC) and the lens (focal length, k1, principal point,
// lens_calibration.hpp), each on a simulated flight whose bearings come through a wrong calibration; and when the lens
// must be held (straight forward flight) or refused (together with the mounting).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "sliding_window_run.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/lens_calibration.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {
namespace {

using testing::RunResult;
using testing::run_estimator;
using testing::sim_config;
using testing::SimRun;

// Online calibration of the camera rotation: the dataset's T_BC is 1.2 deg off the mounting that made the bearings.
// With R_BC fixed the estimate rotates the body to fit the camera; calibrated, the window finds the mounting and the
// attitude error shrinks (the simulated flight turns about all three axes, which makes R_BC observable).
TEST(SlidingWindow, OnlineCameraRotationCalibrationFindsAWrongMounting) {
  const SimRun run = testing::make_sim_run(20.0, 0.5, 13);
  const Eigen::Vector3d phi_true(0.012, -0.010, 0.015);  // R_BC = R_BC0 Exp(phi_true), camera axes [rad]
  SlidingWindowConfig c = sim_config(run, 0.5);
  c.T_BC.linear() = run.T_BC.linear() * geometry::so3_exp(phi_true).transpose();
  SlidingWindowEstimator fixed(c);
  const RunResult r_fixed = run_estimator(fixed, run);
  c.lens_k1_sigma = 0.0;  // the lens and the mounting are not calibrated together
  c.camera_rotation_sigma_deg = 2.0;
  SlidingWindowEstimator calibrated(c);
  const RunResult r_cal = run_estimator(calibrated, run);
  const Eigen::Matrix3d R_err = run.T_BC.linear().transpose() * calibrated.camera_extrinsics().linear();
  const double mounting_error_deg = Eigen::AngleAxisd(R_err).angle() * 180.0 / M_PI;
  std::printf("mounting error after calibration %.3f deg (of %.3f); max attitude error fixed %.3f, calibrated %.3f deg; "
              "rmse %.3f / %.3f m\n", mounting_error_deg, phi_true.norm() * 180.0 / M_PI, r_fixed.max_rotation_deg,
              r_cal.max_rotation_deg, r_fixed.rmse_position_m, r_cal.rmse_position_m);
  EXPECT_EQ(r_cal.not_tracking, 0);
  EXPECT_LT(mounting_error_deg, 0.25);
  EXPECT_LT(r_cal.max_rotation_deg, r_fixed.max_rotation_deg);
  EXPECT_LT(r_cal.rmse_position_m, 0.1);
}

TEST(SlidingWindow, OnlineLensCalibrationFindsAWrongFocalLengthAndK1) {
  // The bearings come through stated intrinsics 0.5 % off in focal length and 0.01 in k1 (the inverse of the
  // correction c_true to first order, lens_calibration.hpp); the principal point is right.
  const SimRun run = testing::make_sim_run(20.0, 0.5, 13);
  const double c_true[4] = {-0.005, -0.01, 0.0, 0.0};
  const double c_bend[4] = {-c_true[0], -c_true[1], 0.0, 0.0};
  const auto bend = [&](std::size_t, std::vector<FeatureBearing>& features) {
    for (auto& f : features) f.f_C = corrected_bearing(f.f_C, c_bend);
  };
  SlidingWindowConfig c = sim_config(run, 0.5);
  c.lens_k1_sigma = 0.0;
  SlidingWindowEstimator stated(c);  // the lens as stated
  const RunResult r_stated = run_estimator(stated, run, bend);
  EXPECT_EQ(stated.lens_correction()[1], 0.0);
  // k1 alone: the other values stay exactly as stated. Freed 2 s after the start (the default waits 20 s).
  c.lens_settle_s = 2.0;
  c.lens_k1_sigma = 0.005;
  SlidingWindowEstimator k1_only(c);
  const RunResult r_k1 = run_estimator(k1_only, run, bend);
  const std::array<double, 4> lens_k1 = k1_only.lens_correction();
  EXPECT_EQ(lens_k1[0], 0.0);
  EXPECT_EQ(lens_k1[2], 0.0);
  EXPECT_EQ(lens_k1[3], 0.0);
  EXPECT_LT(lens_k1[1], -0.005);  // k1 takes up the focal error's share too (both bend the rim inwards)
  EXPECT_LT(r_k1.rmse_position_m, r_stated.rmse_position_m);
  c.lens_scale_sigma = 0.01;
  c.lens_k1_sigma = 0.02;
  c.lens_center_sigma_px = 2.0;
  SlidingWindowEstimator calibrated(c);
  const RunResult r_cal = run_estimator(calibrated, run, bend);
  const std::array<double, 4> lens = calibrated.lens_correction();
  std::printf("lens correction (%.5f, %.5f, %.2f px, %.2f px) of (%.5f, %.5f, 0, 0); rmse stated %.3f m, calibrated "
              "%.3f m (k1 only: %.5f, %.3f m); max rot %.3f / %.3f deg\n", lens[0], lens[1], lens[2] * c.focal_px,
              lens[3] * c.focal_px, c_true[0], c_true[1], r_stated.rmse_position_m, r_cal.rmse_position_m, lens_k1[1],
              r_k1.rmse_position_m, r_stated.max_rotation_deg,
              r_cal.max_rotation_deg);
  EXPECT_EQ(r_cal.not_tracking, 0);
  EXPECT_NEAR(lens[0], c_true[0], 0.003);  // measured -0.0075: 20 s leave some of it to the biases
  EXPECT_NEAR(lens[1], c_true[1], 0.004);
  EXPECT_LT(std::abs(lens[2]) * c.focal_px, 0.5);
  EXPECT_LT(std::abs(lens[3]) * c.focal_px, 0.5);
  EXPECT_LT(r_cal.rmse_position_m, 0.5 * r_stated.rmse_position_m);  // measured 0.376 -> 0.139 m
}

// Straight forward flight (constant heading, the camera's axis within a degree): k1 and depth bend the landmarks alike
// there, and estimated anyway it drifted on wrong-twin-aliased (a straight street) until every registration was ~5 m
// off. Below lens_excitation_deg of rotation over the window the lens is held as it is.
TEST(SlidingWindow, LensIsHeldOnStraightForwardFlight) {
  testing::AnalyticTrajectory straight;
  straight.position = {testing::Sinusoid{-8.0, 0.8, 0.6, 0.6, 0.0}, testing::Sinusoid{0.0, 0.0, 0.1, 0.5, 0.3},
                       testing::Sinusoid{5.0, 0.0, 0.2, 0.8, 1.0}};
  straight.yaw = testing::Sinusoid{0.0, 0.0, 0.005, 0.6, 0.0};
  straight.pitch = testing::Sinusoid{0.0, 0.0, 0.005, 0.9, 0.5};
  straight.roll = testing::Sinusoid{0.0, 0.0, 0.005, 1.3, 2.0};
  const SimRun run = testing::make_sim_run(20.0, 0.5, 13, 2000, 460.0, straight);
  const double c_bend[4] = {0.005, 0.01, 0.0, 0.0};
  const auto bend = [&](std::size_t, std::vector<FeatureBearing>& features) {
    for (auto& f : features) f.f_C = corrected_bearing(f.f_C, c_bend);
  };
  SlidingWindowConfig c = sim_config(run, 0.5);
  c.lens_k1_sigma = 0.005;
  c.lens_settle_s = 0.0;  // only the rotation test holds it
  SlidingWindowEstimator held(c);
  const RunResult r_held = run_estimator(held, run, bend);
  c.lens_excitation_deg = 0.0;  // estimated whatever the motion
  SlidingWindowEstimator always(c);
  const RunResult r_free = run_estimator(always, run, bend);
  std::printf("straight flight: k1 held %.5f (rmse %.3f m), estimated anyway %.5f (rmse %.3f m)\n",
              held.lens_correction()[1], r_held.rmse_position_m, always.lens_correction()[1], r_free.rmse_position_m);
  EXPECT_EQ(r_held.not_tracking, 0);
  EXPECT_EQ(held.lens_correction()[1], 0.0);
  EXPECT_NE(always.lens_correction()[1], 0.0);  // the switch is what held it
  EXPECT_LT(r_held.rmse_position_m, r_free.rmse_position_m);  // measured 0.048 m held, 0.196 m (k1 -0.076) estimated
}

TEST(SlidingWindow, LensCalibrationIsRefusedTogetherWithTheCameraRotation) {
  SlidingWindowConfig c;
  EXPECT_GT(c.lens_k1_sigma, 0.0);  // k1 is estimated by default
  EXPECT_NO_THROW(c.validate());
  c.camera_rotation_sigma_deg = 1.0;
  EXPECT_THROW(c.validate(), InputError);
  c.lens_k1_sigma = 0.0;
  EXPECT_NO_THROW(c.validate());
  c.lens_center_sigma_px = -1.0;
  EXPECT_THROW(c.validate(), InputError);
  c.lens_center_sigma_px = 0.0;
  c.lens_excitation_deg = std::nan("");
  EXPECT_THROW(c.validate(), InputError);
  c.lens_excitation_deg = 10.0;
  c.lens_settle_s = -1.0;
  EXPECT_THROW(c.validate(), InputError);
}

}  // namespace
}  // namespace twinslam::estimator
