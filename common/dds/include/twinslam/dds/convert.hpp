#pragma once
// Conversions between the generated message types and Eigen, in one place for every service and tool.
#include <string>

#include <Eigen/Geometry>

#include "twinslam/dds/types.hpp"

namespace twinslam::dds {

inline msg::Vec3 to_msg(const Eigen::Vector3d& v) {
  msg::Vec3 m;
  m.x(v.x());
  m.y(v.y());
  m.z(v.z());
  return m;
}

// T_AB -> Pose (quaternion w-first, translation p_A of B).
inline msg::Pose to_msg(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  msg::Pose m;
  m.q().w(q.w());
  m.q().x(q.x());
  m.q().y(q.y());
  m.q().z(q.z());
  m.p(to_msg(T.translation()));
  return m;
}

inline Eigen::Vector3d from_msg(const msg::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The quaternion is normalized: a peer may send one rounded to float precision.
inline Eigen::Isometry3d from_msg(const msg::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.q().w(), p.q().x(), p.q().y(), p.q().z()).normalized().toRotationMatrix();
  T.translation() = from_msg(p.p());
  return T;
}

// Lockstep acknowledgement: `service` has finished the camera frame (vehicle, stamp, seq).
inline msg::FrameAck frame_ack(const std::string& vehicle_id, const std::string& service, long long stamp_ns,
                               unsigned long long seq) {
  msg::FrameAck ack;
  ack.vehicle_id(vehicle_id);
  ack.service(service);
  ack.stamp_ns(stamp_ns);
  ack.seq(seq);
  return ack;
}

}  // namespace twinslam::dds
