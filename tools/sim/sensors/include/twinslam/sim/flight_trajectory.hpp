#pragma once
// The simulated drone's motion: body B (= IMU) in the world W (ENU), with exact time derivatives so that the IMU is
// computed, not finite-differenced. Position and yaw are a quintic B-spline (bspline.hpp); roll and pitch follow the
// acceleration like a multirotor's thrust vector (small-angle form): in the yaw-aligned frame,
//   pitch = a_forward / g,  roll = -a_left / g,   R_WB = Rz(yaw) Ry(pitch) Rx(roll)  (ZYX Euler).
// The ZYX body rate is  w_B = [roll' - yaw' sin(pitch);
//                              pitch' cos(roll) + yaw' sin(roll) cos(pitch);
//                              -pitch' sin(roll) + yaw' cos(roll) cos(pitch)],
// and alpha_B = d/dt w_B; both are evaluated with truncated Taylor series (jet.hpp), exact to rounding.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/sim/bspline.hpp"
#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

inline constexpr double kGravity = 9.81;                          // [m/s^2]
inline const Eigen::Vector3d kGravity_W(0.0, 0.0, -kGravity);     // g_W (ENU, up is +z)

struct FlightState {
  double t_s = 0;                                        // simulation time [s]
  // position [m], velocity [m/s], acceleration [m/s^2], jerk [m/s^3] of B in W
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero(), v_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero(), j_W = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();    // orientation of B in W
  // angular velocity [rad/s] and angular acceleration [rad/s^2] of B w.r.t. W, in B
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero(), alpha_B = Eigen::Vector3d::Zero();
  double yaw_rad = 0, yaw_rate_radps = 0;                // heading of body x from east, counter-clockwise

  Eigen::Isometry3d T_WB() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R_WB;
    T.translation() = p_W;
    return T;
  }
};

class FlightTrajectory {
 public:
  explicit FlightTrajectory(QuinticBSpline spline) : spline_(std::move(spline)) {}

  FlightState at(double t_s) const;                      // t clamped into [0, duration()]
  double duration() const { return spline_.duration(); }
  const QuinticBSpline& spline() const { return spline_; }

 private:
  QuinticBSpline spline_;
};

// The scenario's trajectory (loops | survey | waypoints | streets), lasting exactly trajectory.duration_s, starting at
// rest and moving within the first second, with a small zig-zag in the first seconds that excites all IMU axes for
// visual-inertial initialization. Throws InputError naming the key when the scenario cannot be flown within
// flight_limits() (e.g. waypoints too far for duration_s at speed_mps).
//
// `streets` plans on hints.streets (a procedural city's grid), camera forward like `waypoints`: a route that never
// passes an intersection twice, corners rounded to half a street (6 m), and on it
// - a straight stretch of 3 blocks along the street side most lined with facades at least 5 m taller than the
//   drone, flown at altitude_m[0] and 6 m from the nearest footprint of that row (one wall dominating the view);
// - a diagonal across a park block (hints.open_areas_W): an open square, entered and left by 45 deg turns;
// - elsewhere a slow wave through altitude_m (one climb and descent per 600 m), altitude_m[0] >= the street trees'
//   top + 4 m (hints.furniture_top_m), else InputError.
// The skeleton (start, stretch, shortest connection, park, straight tail) grows block by block, at random from the
// seed, until it is as long as the cruise; the stretch comes after about 12 % and the park after about 55 % of it.
FlightTrajectory make_flight_trajectory(const Scenario& scenario, const SceneHints& hints);

// Where a `loops` flight goes, so the world can keep that ring free of other buildings: counter-clockwise circles
// around hints.tall_building_center_W starting south of it, from altitude z_start_m rising by rise_m in total.
struct LoopsGeometry {
  Eigen::Vector2d center_W = Eigen::Vector2d::Zero();  // [m, E N]
  double radius_m = 0;     // tall_building_radius_m + 6..30 m (< clear_radius_m - 3), for trajectory.loops loops
  double turns = 0;        // loops actually flown (differs from trajectory.loops when the radius is clamped)
  double z_start_m = 0;    // [m, W up]
  double rise_m = 0;       // [m]
};
LoopsGeometry loops_geometry(const Scenario& scenario, const SceneHints& hints);

}  // namespace twinslam::sim
