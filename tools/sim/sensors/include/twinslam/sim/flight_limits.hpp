#pragma once
// Drone-like limits of a simulated flight and their check: a trajectory a real multirotor could not fly would give
// the estimator an unrealistically easy or hard problem.
#include <string>

#include "twinslam/sim/flight_trajectory.hpp"

namespace twinslam::sim {

struct FlightLimits {
  double max_speed_mps = 2.5;       // [m/s] (flight_limits(): 1.25 x speed_mps + 0.5)
  double max_accel_mps2 = 3.0;      // norm of the acceleration in W [m/s^2]
  double max_jerk_mps3 = 10.0;      // norm of the jerk in W [m/s^3]: tilt rate ~ jerk / g, so about 60 deg/s
  double max_yaw_rate_dps = 45.0;   // [deg/s]
  double max_tilt_deg = 25.0;       // angle between body z and up [deg]
};

FlightLimits flight_limits(const TrajectoryConfig& config);

struct FlightStats {
  double max_speed_mps = 0, max_accel_mps2 = 0, max_yaw_rate_dps = 0, max_tilt_deg = 0;
  double max_jerk_mps3 = 0;         // norm of the jerk in W [m/s^3]
  double max_body_rate_dps = 0;     // norm of w_B [deg/s]
  double length_m = 0;              // path length [m]
  double min_up_m = 0, max_up_m = 0;  // altitude range of p_W.z [m]
  double time_to_move_s = 0;        // first time the speed exceeds 5 cm/s [s]
};

// Samples the trajectory every sample_dt [s].
FlightStats measure_flight(const FlightTrajectory& trajectory, double sample_dt = 0.02);

// InputError "WHAT: trajectory.KEY: ..." naming the limit exceeded (speed -> trajectory.speed_mps, others ->
// trajectory.type, since the path shape causes them).
void check_flight_limits(const FlightStats& stats, const FlightLimits& limits, const std::string& what);

}  // namespace twinslam::sim
