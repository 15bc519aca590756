// Flight trajectories: spline continuity and exact derivatives, the shapes the issue asks for (three rising loops
// around the building with the camera toward it, a ~500 m survey, waypoints), drone-like limits and an early start.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

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

std::string trajectory_error(const Scenario& sc, const SceneHints& hints) {
  try {
    make_flight_trajectory(sc, hints);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// 2.3 km through the streets of the default city's grid (test_support.hpp: no buildings, one park).
Scenario streets_scenario() {
  Scenario sc = builtin_scenario("city-loops");
  sc.name = "streets";
  sc.trajectory.type = "streets";
  sc.trajectory.duration_s = 780;
  sc.trajectory.speed_mps = 3;
  sc.trajectory.altitude_m = {15, 35};
  return sc;
}

TEST(SimFlight, StreetsStayOnTheStreetsOncePerIntersectionLookingForward) {
  const Scenario sc = streets_scenario();
  const SceneHints hints = hints_for(sc);
  const FlightTrajectory f = make_flight_trajectory(sc, hints);
  const StreetGrid& grid = hints.streets;
  const Eigen::Vector4d& park = hints.open_areas_W.front();
  std::map<std::pair<int, int>, int> visits;  // intersection -> separate passes through its centre square
  std::pair<int, int> inside{-1, -1};
  int forward = 0, moving = 0;
  for (double t = 0; t <= f.duration(); t += 0.2) {
    const FlightState s = f.at(t);
    const Eigen::Vector2d p = s.p_W.head<2>();
    auto nearest = [](const std::vector<double>& lines, double x) {
      int k = 0;
      for (int i = 1; i < static_cast<int>(lines.size()); ++i)
        if (std::abs(lines[i] - x) < std::abs(lines[k] - x)) k = i;
      return k;
    };
    const int i = nearest(grid.east_m, p.x()), j = nearest(grid.north_m, p.y());
    const double off_e = std::abs(p.x() - grid.east_m[i]), off_n = std::abs(p.y() - grid.north_m[j]);
    const bool in_park = p.x() > park[0] - 6 && p.x() < park[2] + 6 && p.y() > park[1] - 6 && p.y() < park[3] + 6;
    ASSERT_TRUE(std::min(off_e, off_n) <= 0.5 * grid.width_m || in_park) << "off the streets at t " << t;
    const std::pair<int, int> here = off_e < 0.5 * grid.width_m && off_n < 0.5 * grid.width_m
                                         ? std::make_pair(i, j) : std::make_pair(-1, -1);
    if (here != inside && here.first >= 0) ++visits[here];
    inside = here;
    if (s.v_W.head<2>().norm() > 1.0) {
      ++moving;
      const Eigen::Vector3d axis_W = s.R_WB * camera_T_BC(sc).linear().col(2);
      forward += axis_W.head<2>().normalized().dot(s.v_W.head<2>().normalized()) > std::cos(10 * M_PI / 180);
    }
  }
  for (const auto& [node, n] : visits) EXPECT_EQ(n, 1) << "intersection " << node.first << "," << node.second;
  EXPECT_GE(visits.size(), 30u);  // 2.3 km over 60 m blocks
  EXPECT_GT(forward, 0.9 * moving);  // camera along the street but in the turns
  // The diagonal across the park: its centre is flown over.
  double to_park = 1e9;
  for (double t = 0; t <= f.duration(); t += 0.2)
    to_park = std::min(to_park, (f.at(t).p_W.head<2>() - 0.5 * (park.head<2>() + park.tail<2>())).norm());
  EXPECT_LT(to_park, 2.0);
}

TEST(SimFlight, StreetsNameWhatStopsThem) {
  Scenario sc = streets_scenario();
  SceneHints hints = hints_for(sc);
  sc.trajectory.altitude_m = {6, 30};  // into the 10 m street trees
  EXPECT_NE(trajectory_error(sc, hints).find("streets: trajectory.altitude_m: a streets flight must stay >= 14 m"),
            std::string::npos) << trajectory_error(sc, hints);
  sc = streets_scenario();
  EXPECT_NE(trajectory_error(sc, city_hints(600, 19.8)).find("streets: trajectory.type: streets needs a street grid"),
            std::string::npos);
  sc.city.size_m = 200;  // 3 x 3 blocks: 2 x 2 intersections, no 3-block stretch
  EXPECT_NE(trajectory_error(sc, hints_for(sc)).find("streets: city.size_m: the street grid (2 x 2 intersections)"),
            std::string::npos) << trajectory_error(sc, hints_for(sc));
  sc = streets_scenario();
  sc.trajectory.duration_s = 3600;  // 10.8 km do not fit 8 x 8 intersections without repeating a street
  EXPECT_NE(trajectory_error(sc, hints).find("streets: city.size_m: the street grid (8 x 8 intersections) holds no"),
            std::string::npos) << trajectory_error(sc, hints);
  hints.open_areas_W.clear();
  sc = streets_scenario();
  EXPECT_NE(trajectory_error(sc, hints).find("city.size_m: no park"), std::string::npos);
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
