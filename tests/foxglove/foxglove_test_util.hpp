#pragma once
// Helpers of the common/foxglove tests: messages with poses, and the PointCloud's base64 data read back.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "twinslam/foxglove/well_known.hpp"

namespace twinslam::foxglove::test {

inline msg::Pose pose(const Eigen::Isometry3d& T) {
  msg::Pose p;
  const Eigen::Quaterniond q(T.linear());
  p.q().w(q.w()); p.q().x(q.x()); p.q().y(q.y()); p.q().z(q.z());
  p.p().x(T.translation().x()); p.p().y(T.translation().y()); p.p().z(T.translation().z());
  return p;
}

inline Eigen::Isometry3d transform(double yaw_deg, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = t;
  return T;
}

// The cloud's points (x, y, z, quality as float32, stride 16) from its base64 data.
inline std::vector<std::array<float, 4>> cloud_points(const nlohmann::json& cloud) {
  const std::string text = cloud["data"].get<std::string>();
  std::vector<std::uint8_t> bytes;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    acc = (acc << 6) | static_cast<std::uint32_t>(std::strchr(alphabet, c) - alphabet);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<std::uint8_t>(acc >> bits));
    }
  }
  std::vector<std::array<float, 4>> out(bytes.size() / 16);
  std::memcpy(out.data(), bytes.data(), out.size() * 16);
  return out;
}

inline msg::LocalMap local_map(const std::string& vehicle, std::int64_t stamp, const Eigen::Isometry3d& T_WL,
                               const std::vector<Eigen::Vector3d>& p_L) {
  msg::LocalMap m;
  m.vehicle_id(vehicle);
  m.keyframe_stamp_ns(stamp);
  m.T_WL(pose(T_WL));
  m.T_LB(pose(Eigen::Isometry3d::Identity()));
  for (std::size_t i = 0; i < p_L.size(); ++i) {
    msg::Landmark l;
    l.id(i);
    l.p_L().x(p_L[i].x()); l.p_L().y(p_L[i].y()); l.p_L().z(p_L[i].z());
    l.quality(0.25f * static_cast<float>(i % 4));
    m.landmarks().push_back(l);
  }
  return m;
}

}  // namespace twinslam::foxglove::test
