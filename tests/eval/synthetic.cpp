#include "synthetic.hpp"

#include <cmath>

namespace twinslam::test {

Eigen::Matrix3d rotation_zyx(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Trajectory helix(std::size_t n, std::int64_t dt_ns, std::int64_t t0_ns) {
  Trajectory t;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) * static_cast<double>(dt_ns) * 1e-9;  // [s]
    const double phi = 0.05 * s;                                                  // 1 m/s on a 20 m radius
    StampedPose pose;
    pose.stamp_ns = t0_ns + static_cast<std::int64_t>(k) * dt_ns;
    pose.T_XB.translation() = Eigen::Vector3d(20.0 * std::cos(phi), 20.0 * std::sin(phi), 0.1 * s + std::sin(0.3 * s));
    pose.T_XB.linear() = rotation_zyx(phi + M_PI / 2, 0.05 * std::sin(0.7 * s), 0.08 * std::cos(0.4 * s));
    t.poses.push_back(pose);
  }
  return t;
}

Trajectory straight_line(std::size_t n, double v_mps, std::int64_t dt_ns, std::int64_t t0_ns) {
  Trajectory t;
  for (std::size_t k = 0; k < n; ++k) {
    StampedPose pose;
    pose.stamp_ns = t0_ns + static_cast<std::int64_t>(k) * dt_ns;
    pose.T_XB.translation() = Eigen::Vector3d(v_mps * static_cast<double>(k) * static_cast<double>(dt_ns) * 1e-9, 0, 0);
    t.poses.push_back(pose);
  }
  return t;
}

Trajectory transformed(const Trajectory& t, const eval::Similarity& S) {
  Trajectory out = t;
  for (auto& pose : out.poses) pose.T_XB = S.apply(pose.T_XB);
  return out;
}

eval::Similarity inverse(const eval::Similarity& S) {
  // p_W = s R p_L + t  =>  p_L = (1/s) R^T p_W - (1/s) R^T t
  eval::Similarity inv;
  inv.scale = 1.0 / S.scale;
  inv.R_WL = S.R_WL.transpose();
  inv.t_W = -inv.scale * inv.R_WL * S.t_W;
  return inv;
}

}  // namespace twinslam::test
