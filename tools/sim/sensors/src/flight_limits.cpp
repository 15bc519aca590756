#include "twinslam/sim/flight_limits.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "twinslam/core/error.hpp"

namespace twinslam::sim {

FlightLimits flight_limits(const TrajectoryConfig& config) {
  FlightLimits l;
  l.max_speed_mps = 1.25 * config.speed_mps + 0.5;  // cruise plus the start-up zig-zag and turn overshoot
  return l;
}

FlightStats measure_flight(const FlightTrajectory& trajectory, double sample_dt) {
  FlightStats st;
  st.min_up_m = st.max_up_m = trajectory.at(0).p_W.z();
  st.time_to_move_s = -1;
  Eigen::Vector3d previous = trajectory.at(0).p_W;
  const auto n = static_cast<long>(std::floor(trajectory.duration() / sample_dt));
  for (long k = 0; k <= n; ++k) {
    const FlightState s = trajectory.at(static_cast<double>(k) * sample_dt);
    const double speed = s.v_W.norm();
    st.max_speed_mps = std::max(st.max_speed_mps, speed);
    st.max_accel_mps2 = std::max(st.max_accel_mps2, s.a_W.norm());
    st.max_jerk_mps3 = std::max(st.max_jerk_mps3, s.j_W.norm());
    st.max_yaw_rate_dps = std::max(st.max_yaw_rate_dps, std::abs(s.yaw_rate_radps) * 180 / M_PI);
    st.max_body_rate_dps = std::max(st.max_body_rate_dps, s.w_B.norm() * 180 / M_PI);
    const double tilt = std::acos(std::clamp(s.R_WB(2, 2), -1.0, 1.0)) * 180 / M_PI;
    st.max_tilt_deg = std::max(st.max_tilt_deg, tilt);
    st.min_up_m = std::min(st.min_up_m, s.p_W.z());
    st.max_up_m = std::max(st.max_up_m, s.p_W.z());
    st.length_m += (s.p_W - previous).norm();
    previous = s.p_W;
    if (st.time_to_move_s < 0 && speed > 0.05) st.time_to_move_s = s.t_s;
  }
  return st;
}

void check_flight_limits(const FlightStats& st, const FlightLimits& l, const std::string& what) {
  auto fail = [&](const std::string& key, const std::string& quantity, double value, double limit) {
    std::ostringstream m;
    m << key << ": the flight reaches " << quantity << " " << value << " (limit " << limit << ")";
    throw InputError(where(what, 0, m.str()));
  };
  if (st.max_speed_mps > l.max_speed_mps) fail("trajectory.speed_mps", "speed [m/s]", st.max_speed_mps, l.max_speed_mps);
  if (st.max_accel_mps2 > l.max_accel_mps2)
    fail("trajectory.type", "acceleration [m/s^2]", st.max_accel_mps2, l.max_accel_mps2);
  if (st.max_jerk_mps3 > l.max_jerk_mps3) fail("trajectory.type", "jerk [m/s^3]", st.max_jerk_mps3, l.max_jerk_mps3);
  if (st.max_yaw_rate_dps > l.max_yaw_rate_dps)
    fail("trajectory.type", "yaw rate [deg/s]", st.max_yaw_rate_dps, l.max_yaw_rate_dps);
  if (st.max_tilt_deg > l.max_tilt_deg) fail("trajectory.type", "tilt [deg]", st.max_tilt_deg, l.max_tilt_deg);
}

}  // namespace twinslam::sim
