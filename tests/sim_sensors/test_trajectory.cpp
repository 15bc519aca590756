// Flight trajectories: spline continuity and exact derivatives, the shapes the issue asks for (three rising loops
// around the building with the camera toward it, a ~500 m survey, waypoints), drone-like limits and an early start.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/geometry/so3.hpp"
#include "twinslam/sim/flight_limits.hpp"

namespace twinslam::sim {
namespace {

using testing::city_hints;
using testing::hints_for;

QuinticBSpline random_spline() {
  std::vector<Eigen::Vector4d> cps;
  std::srand(3);
  for (int i = 0; i < 12; ++i) cps.push_back(Eigen::Vector4d::Random() * 5);
  return QuinticBSpline(cps, 0.7);
}

TEST(SimBSpline, ConstantControlPointsGiveAConstant) {
  const QuinticBSpline s(std::vector<Eigen::Vector4d>(8, Eigen::Vector4d(1, -2, 3, 0.5)), 1.0);
  for (double t : {0.0, 0.3, 1.7, 2.999}) {
    const auto d = s.derivatives(t);
    EXPECT_TRUE(d[0].isApprox(Eigen::Vector4d(1, -2, 3, 0.5), 1e-12));
    for (int k = 1; k < 5; ++k) EXPECT_LT(d[static_cast<std::size_t>(k)].norm(), 1e-9);
  }
}

TEST(SimBSpline, DerivativesMatchNumericAndAreContinuousAtKnots) {
  const QuinticBSpline s = random_spline();
  const double h = 1e-5;
  for (double t : {0.35, 1.45, 2.2, 3.9}) {  // off the knots: the 5th derivative jumps there
    const auto d = s.derivatives(t), dp = s.derivatives(t + h), dm = s.derivatives(t - h);
    for (std::size_t k = 1; k < 5; ++k) {
      const Eigen::Vector4d numeric = (dp[k - 1] - dm[k - 1]) / (2 * h);
      EXPECT_LT((numeric - d[k]).norm(), 1e-5 * (1 + d[k].norm())) << "order " << k << " t " << t;
    }
  }
  // C4: value and derivatives up to order 4 agree on both sides of a knot (t = 2 * 0.7).
  const double knot = 1.4, e = 1e-10;
  const auto left = s.derivatives(knot - e), right = s.derivatives(knot + e);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_LT((left[k] - right[k]).norm(), 1e-6) << "order " << k;
}

TEST(SimFlight, BodyRatesAndAccelerationsMatchNumericDerivatives) {
  const Scenario sc = builtin_scenario("city-loops");
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  const double h = 1e-4;
  for (double t : {2.5, 5.3, 40.0, 151.7}) {
    const FlightState s = f.at(t), sp = f.at(t + h), sm = f.at(t - h);
    EXPECT_LT(((sp.p_W - sm.p_W) / (2 * h) - s.v_W).norm(), 1e-6);
    EXPECT_LT(((sp.v_W - sm.v_W) / (2 * h) - s.a_W).norm(), 1e-6);
    EXPECT_LT(((sp.a_W - sm.a_W) / (2 * h) - s.j_W).norm(), 1e-5);
    // R(t+h) = R(t-h) Exp(w 2h) to second order
    const Eigen::Vector3d w_numeric = geometry::so3_log(sm.R_WB.transpose() * sp.R_WB) / (2 * h);
    EXPECT_LT((w_numeric - s.w_B).norm(), 1e-7) << "t " << t;
    EXPECT_LT(((sp.w_B - sm.w_B) / (2 * h) - s.alpha_B).norm(), 1e-6) << "t " << t;
    EXPECT_NEAR(s.R_WB.determinant(), 1.0, 1e-12);
  }
}

TEST(SimFlight, BuiltinsRespectDroneLimitsAndStartMovingEarly) {
  for (const auto& name : builtin_scenario_names()) {
    const Scenario sc = builtin_scenario(name);
    const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));  // throws if a limit is exceeded
    const FlightStats st = measure_flight(f, 0.01);
    const FlightLimits lim = flight_limits(sc.trajectory);
    EXPECT_NEAR(f.duration(), sc.trajectory.duration_s, 1e-9) << name;
    EXPECT_LE(st.max_speed_mps, lim.max_speed_mps) << name;
    EXPECT_LE(st.max_accel_mps2, 3.0) << name;
    EXPECT_LE(st.max_jerk_mps3, lim.max_jerk_mps3) << name;
    EXPECT_LE(st.max_yaw_rate_dps, 45.0) << name;
    EXPECT_LE(st.max_tilt_deg, 25.0) << name;
    EXPECT_GE(st.min_up_m, sc.trajectory.altitude_m[0] - 1.0) << name;
    EXPECT_LE(st.max_up_m, sc.trajectory.altitude_m[1] + 1.0) << name;
    EXPECT_LE(st.time_to_move_s, 1.0) << name;
    EXPECT_GE(st.time_to_move_s, 0.0) << name;
    const FlightState end = f.at(f.duration());
    EXPECT_LT(end.v_W.norm(), 1e-9) << name;  // comes to rest
    std::printf("%-12s length %.1f m, max speed %.2f m/s, accel %.2f m/s^2, jerk %.2f m/s^3, yaw rate %.1f deg/s, "
                "tilt %.1f deg, moving after %.2f s\n",
                name.c_str(), st.length_m, st.max_speed_mps, st.max_accel_mps2, st.max_jerk_mps3, st.max_yaw_rate_dps,
                st.max_tilt_deg, st.time_to_move_s);
  }
}

TEST(SimFlight, FirstSecondsExciteEveryImuAxis) {
  const Scenario sc = builtin_scenario("city-loops");
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  Eigen::Vector3d w_max = Eigen::Vector3d::Zero(), a_max = Eigen::Vector3d::Zero();
  for (double t = 0; t < 8.0; t += 0.01) {
    const FlightState s = f.at(t);
    w_max = w_max.cwiseMax(s.w_B.cwiseAbs());
    a_max = a_max.cwiseMax((s.R_WB.transpose() * s.a_W).cwiseAbs());
  }
  EXPECT_GT(w_max.minCoeff(), 0.05) << w_max.transpose();  // [rad/s] on every gyro axis
  EXPECT_GT(a_max.minCoeff(), 0.3) << a_max.transpose();   // [m/s^2] on every axis, besides gravity
}

TEST(SimFlight, LoopsCircleTheBuildingThreeTimesRisingWithCameraTowardIt) {
  const Scenario sc = builtin_scenario("city-loops");
  const SceneHints hints = city_hints(600, 15);
  const FlightTrajectory f = make_flight_trajectory(sc, hints);
  const Eigen::Isometry3d T_BC = camera_T_BC(sc);
  double angle = 0, previous = 0;
  double min_r = 1e9, max_r = 0;
  for (double t = 0; t <= f.duration(); t += 0.1) {
    const FlightState s = f.at(t);
    const Eigen::Vector2d rel = s.p_W.head<2>() - hints.tall_building_center_W;
    const double a = std::atan2(rel.y(), rel.x());
    if (t > 0) angle += std::remainder(a - previous, 2 * M_PI);
    previous = a;
    if (t > 10 && t < f.duration() - 10) {
      min_r = std::min(min_r, rel.norm());
      max_r = std::max(max_r, rel.norm());
      // Optical axis (horizontal part) about 45 deg from the direction to the building.
      const Eigen::Vector3d axis_W = s.R_WB * T_BC.linear().col(2);
      const double c = -rel.normalized().dot(axis_W.head<2>().normalized());
      EXPECT_NEAR(std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI, 45.0, 12.0) << "t " << t;
    }
  }
  EXPECT_NEAR(angle / (2 * M_PI), 3.0, 0.1);  // three counter-clockwise loops
  // Stays on the published ring (the world keeps it free of other buildings).
  const LoopsGeometry g = loops_geometry(sc, hints);
  EXPECT_GE(g.radius_m, hints.tall_building_radius_m + 6);
  EXPECT_NEAR(g.turns, 3.0, 0.1);
  EXPECT_GT(min_r, g.radius_m - 1.0);
  EXPECT_LT(max_r, g.radius_m + 1.0);
  const double rise = f.at(f.duration()).p_W.z() - f.at(0).p_W.z();
  EXPECT_NEAR(rise, 3 * sc.trajectory.loop_rise_m, 1.0);
  EXPECT_GT(f.at(100).p_W.z(), f.at(20).p_W.z() + 1.0);
}

TEST(SimFlight, LoopsStayInsideTheClearZoneOfTheWorld) {
  const Scenario sc = builtin_scenario("city-loops");
  SceneHints hints = city_hints(600, 19.8);  // the procedural city's 28 m x 28 m tower
  hints.clear_radius_m = 36;                 // its block half-width + one street
  const LoopsGeometry g = loops_geometry(sc, hints);
  EXPECT_GE(g.radius_m, 19.8 + 6 - 1e-9);
  EXPECT_LE(g.radius_m, 33 + 1e-9);
  EXPECT_NEAR(g.turns, 3.0, 0.1);  // 500 m fits three loops at 26.7 m
  hints.clear_radius_m = 28;       // a tight plaza: the ring shrinks, more loops are flown
  EXPECT_NEAR(loops_geometry(sc, hints).radius_m, 25, 1e-9);
  EXPECT_NO_THROW(make_flight_trajectory(sc, hints));
}

TEST(SimFlight, SurveyFliesAbout500mOverTheBlocksLookingDownForward) {
  const Scenario sc = builtin_scenario("city-survey");
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  const FlightStats st = measure_flight(f);
  EXPECT_NEAR(st.length_m, 500, 50);
  EXPECT_GE(st.min_up_m, sc.city.height_m[1]);
  const Eigen::Vector3d axis_W = f.at(60).R_WB * camera_T_BC(sc).linear().col(2);
  EXPECT_NEAR(std::asin(-axis_W.z()) * 180 / M_PI, 45.0, 15.0);  // camera pitched about 45 deg down
}

TEST(SimFlight, WaypointsArePassedAndTooShortDurationIsNamed) {
  Scenario sc = builtin_scenario("tiny");
  sc.trajectory.type = "waypoints";
  sc.trajectory.duration_s = 60;
  sc.trajectory.speed_mps = 2;
  sc.trajectory.waypoints_W = {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(40, 0, 6), Eigen::Vector3d(40, 30, 8)};
  const FlightTrajectory f = make_flight_trajectory(sc, hints_for(sc));
  for (const auto& w : sc.trajectory.waypoints_W) {
    double best = 1e9;
    for (double t = 0; t <= f.duration(); t += 0.05) best = std::min(best, (f.at(t).p_W - w).norm());
    EXPECT_LT(best, 4.0) << w.transpose();  // corners are rounded (8 m fillets), ends are exact
  }
  EXPECT_LT((f.at(0).p_W - sc.trajectory.waypoints_W.front()).norm(), 1e-9);
  EXPECT_LT((f.at(f.duration()).p_W - sc.trajectory.waypoints_W.back()).norm(), 1e-9);

  sc.trajectory.duration_s = 20;  // 70 m at 2 m/s does not fit
  try {
    make_flight_trajectory(sc, hints_for(sc));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("trajectory.duration_s"), std::string::npos) << e.what();
  }
}

TEST(SimFlight, TooFastIsRejectedNamingTheKey) {
  Scenario sc = builtin_scenario("tiny");
  sc.trajectory.speed_mps = 12;  // 12 m/s on a ~20 m radius: 7 m/s^2
  try {
    make_flight_trajectory(sc, hints_for(sc));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tiny: trajectory."), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace twinslam::sim
