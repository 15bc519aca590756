#include "twinslam/foxglove/derived_channels.hpp"

#include <cmath>
#include <exception>

namespace twinslam::foxglove {
namespace {

double distance(const PoseW& a, const PoseW& b) {
  return std::hypot(a.p[0] - b.p[0], a.p[1] - b.p[1], a.p[2] - b.p[2]);
}
bool finite(const PoseW& T) {
  for (double v : T.p) if (!std::isfinite(v)) return false;
  for (double v : T.q) if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

std::string DerivedChannels::prefix(const std::string& vehicle_id) {
  return "/" + (vehicle_id.empty() ? std::string("unnamed") : vehicle_id);
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::Odometry& m, bool render) {
  const std::string v = prefix(m.vehicle_id());
  std::vector<DerivedMessage> out;
  if (render) out.push_back({v + "/estimate/pose", &pose_in_frame_schema(), pose_json(m), std::nullopt});
  if (m.status() != msg::ODOM_TRACKING && m.status() != msg::ODOM_ALIGNED) return out;  // no pose to draw yet
  const PoseW T = pose_of(m.T_WB());
  if (!finite(T)) return out;
  std::lock_guard lock(mutex_);
  auto& path = vehicles_[m.vehicle_id()].path;
  if (!path.empty() && distance(path.back(), T) < config_.path_spacing_m) return out;
  if (path.size() >= config_.max_path_poses) {
    std::vector<PoseW> half;
    for (std::size_t i = 0; i < path.size(); i += 2) half.push_back(path[i]);
    path = std::move(half);
  }
  path.push_back(T);
  if (render) {
    out.push_back({v + "/estimate/path", &poses_in_frame_schema(), path_json(m.stamp_ns(), path), std::nullopt});
  }
  return out;
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::GnssFix& m, bool render) {
  if (!render) return {};
  return {{prefix(m.vehicle_id()) + "/gnss", &location_fix_schema(), location_fix_json(m), std::nullopt}};
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::LocalMap& m, bool render) {
  {
    std::lock_guard lock(mutex_);
    auto& maps = vehicles_[m.vehicle_id()].local_maps;
    maps.push_back(m);
    while (maps.size() > config_.kept_local_maps) maps.pop_front();
  }
  if (!render) return {};
  return {{prefix(m.vehicle_id()) + "/landmarks", &point_cloud_schema(), landmarks_json(m), std::nullopt}};
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::Registration& m, bool render) {
  if (!render) return {};
  const std::string v = prefix(m.vehicle_id());
  std::vector<DerivedMessage> out{
      {v + "/registration", &registration_health_schema(), registration_health_json(m), std::nullopt}};
  if (m.status() != msg::REG_ACCEPTED) return out;
  std::lock_guard lock(mutex_);
  for (const msg::LocalMap& map : vehicles_[m.vehicle_id()].local_maps) {
    if (map.keyframe_stamp_ns() == m.keyframe_stamp_ns()) {
      out.push_back(
          {v + "/landmarks/registered", &point_cloud_schema(), landmarks_json(map, &m.correction_W()), std::nullopt});
      break;
    }
  }
  return out;
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::MapTile& m, bool /*render*/) {  // latched: always
  try {
    return {{"/twin/tiles", &scene_update_schema(), tile_scene_json(m), m.tile_key()}};
  } catch (const std::exception&) {  // InputError from the decoder; anything Draco throws
    std::lock_guard lock(mutex_);
    ++tiles_undecodable_;
    return {};
  }
}

std::uint64_t DerivedChannels::tiles_undecodable() const {
  std::lock_guard lock(mutex_);
  return tiles_undecodable_;
}

}  // namespace twinslam::foxglove
