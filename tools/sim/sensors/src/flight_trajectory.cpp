// Attitude and body rates of the flight from the spline's position/yaw derivatives (see flight_trajectory.hpp).
#include "twinslam/sim/flight_trajectory.hpp"

#include "jet.hpp"

namespace twinslam::sim {

using detail::Jet;

FlightState FlightTrajectory::at(double t_s) const {
  const auto d = spline_.derivatives(t_s);  // d[k] = k-th derivative of (e, n, u, yaw)
  FlightState s;
  s.t_s = t_s;
  s.p_W = d[0].head<3>();
  s.v_W = d[1].head<3>();
  s.a_W = d[2].head<3>();
  s.j_W = d[3].head<3>();
  s.yaw_rad = d[0][3];
  s.yaw_rate_radps = d[1][3];

  // Second-order series of yaw and of the acceleration (whose derivatives are jerk and snap).
  const Jet yaw = Jet::from_derivatives(d[0][3], d[1][3], d[2][3]);
  const Jet ax = Jet::from_derivatives(d[2][0], d[3][0], d[4][0]);
  const Jet ay = Jet::from_derivatives(d[2][1], d[3][1], d[4][1]);
  Jet sy, cy;
  detail::sincos(yaw, sy, cy);
  const Jet a_forward = cy * ax + sy * ay;   // acceleration along the yaw-aligned x axis [m/s^2]
  const Jet a_left = cy * ay - sy * ax;      // along the yaw-aligned y axis [m/s^2]
  const Jet pitch = (1.0 / kGravity) * a_forward;
  const Jet roll = (-1.0 / kGravity) * a_left;

  s.R_WB = (Eigen::AngleAxisd(yaw.value(), Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(pitch.value(), Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(roll.value(), Eigen::Vector3d::UnitX()))
               .toRotationMatrix();

  Jet sp, cp, sr, cr;
  detail::sincos(pitch, sp, cp);
  detail::sincos(roll, sr, cr);
  const Jet dyaw = yaw.derivative(), dpitch = pitch.derivative(), droll = roll.derivative();
  const Jet wx = droll - dyaw * sp;
  const Jet wy = dpitch * cr + dyaw * sr * cp;
  const Jet wz = dyaw * cr * cp - dpitch * sr;
  s.w_B = Eigen::Vector3d(wx.c0, wy.c0, wz.c0);
  s.alpha_B = Eigen::Vector3d(wx.c1, wy.c1, wz.c1);
  return s;
}

}  // namespace twinslam::sim
