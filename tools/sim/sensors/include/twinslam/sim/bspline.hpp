#pragma once
// Uniform quintic B-spline in time over 4-vectors (east, north, up, yaw): C4-continuous, so position has continuous
// velocity, acceleration, jerk and snap, and the attitude derived from acceleration (flight_trajectory.hpp) has a
// continuous angular acceleration. Matrix form of Qin, "General matrix representations for B-splines" (2000): on
// segment i with u = t/dt - i in [0, 1),  x(u) = [1 u u^2 ... u^5] M [c_i ... c_{i+5}]^T.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace twinslam::sim {

class QuinticBSpline {
 public:
  static constexpr int kDegree = 5;

  // Needs at least kDegree + 1 control points; knot spacing dt [s] > 0. Spline time runs over [0, duration()].
  QuinticBSpline(std::vector<Eigen::Vector4d> control_points, double dt);

  double duration() const { return dt_ * static_cast<double>(segments()); }
  double knot_spacing() const { return dt_; }
  std::size_t segments() const { return control_points_.size() - kDegree; }
  const std::vector<Eigen::Vector4d>& control_points() const { return control_points_; }

  // Value and time derivatives of order 0..4 at time t [s] (clamped into [0, duration()]).
  std::array<Eigen::Vector4d, 5> derivatives(double t) const;

 private:
  std::vector<Eigen::Vector4d> control_points_;
  double dt_;
};

}  // namespace twinslam::sim
