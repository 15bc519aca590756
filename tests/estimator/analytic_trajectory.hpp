#pragma once
// A smooth analytic trajectory of body B in a gravity-aligned frame W with closed-form derivatives, so that ideal IMU
// measurements (body rate and specific force) are exact rather than finite differences. Header-only, depends only on
// Eigen, so the simulator can reuse it.
//
// Position: per axis p(t) = c + d t + A sin(w t + phase).
// Orientation: R_WB = Rz(yaw) Ry(pitch) Rx(roll) (ZYX Euler), each angle = c + d t + A sin(w t + phase); the body rate
// of ZYX angles is  omega_B = [roll' - yaw' sin(pitch);
//                              pitch' cos(roll) + yaw' sin(roll) cos(pitch);
//                              -pitch' sin(roll) + yaw' cos(roll) cos(pitch)].
#include <array>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::testing {

// x(t) = c + d t + A sin(w t + phase) and its first two derivatives.
struct Sinusoid {
  double c = 0.0, d = 0.0, A = 0.0, w = 1.0, phase = 0.0;
  double value(double t) const { return c + d * t + A * std::sin(w * t + phase); }
  double rate(double t) const { return d + A * w * std::cos(w * t + phase); }
  double accel(double t) const { return -A * w * w * std::sin(w * t + phase); }
};

struct TrajectoryPoint {
  Eigen::Vector3d p_W, v_W, a_W;  // position [m], velocity [m/s], acceleration [m/s^2] of B in W
  Eigen::Matrix3d R_WB;           // orientation of B in W
  Eigen::Vector3d omega_B;        // angular velocity of B w.r.t. W, in B [rad/s]
};

class AnalyticTrajectory {
 public:
  // Defaults: a drone-like motion, accelerations up to ~1 m/s^2, body rates up to ~0.5 rad/s, pitch/roll < 0.2 rad.
  std::array<Sinusoid, 3> position{Sinusoid{0.0, 1.0, 3.0, 0.5, 0.0}, Sinusoid{1.0, 0.0, 2.0, 0.7, 0.3},
                                   Sinusoid{5.0, 0.1, 0.5, 1.1, 1.0}};
  Sinusoid yaw{0.3, 0.2, 0.5, 0.6, 0.0};
  Sinusoid pitch{0.0, 0.0, 0.2, 0.9, 0.5};
  Sinusoid roll{0.0, 0.0, 0.15, 1.3, 2.0};

  TrajectoryPoint at(double t) const {
    TrajectoryPoint s;
    for (int k = 0; k < 3; ++k) {
      s.p_W[k] = position[k].value(t);
      s.v_W[k] = position[k].rate(t);
      s.a_W[k] = position[k].accel(t);
    }
    const double y = yaw.value(t), p = pitch.value(t), r = roll.value(t);
    const double dy = yaw.rate(t), dp = pitch.rate(t), dr = roll.rate(t);
    s.R_WB = (Eigen::AngleAxisd(y, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX()))
                 .toRotationMatrix();
    s.omega_B = Eigen::Vector3d(dr - dy * std::sin(p), dp * std::cos(r) + dy * std::sin(r) * std::cos(p),
                                -dp * std::sin(r) + dy * std::cos(r) * std::cos(p));
    return s;
  }

  // What an ideal accelerometer measures: f_B = R_WB^T (a_W - g_W) [m/s^2].
  Eigen::Vector3d specific_force_B(double t, const Eigen::Vector3d& g_W) const {
    const TrajectoryPoint s = at(t);
    return s.R_WB.transpose() * (s.a_W - g_W);
  }
};

}  // namespace twinslam::testing
