#include "twinslam/foxglove/derived_channels.hpp"

#include <cmath>
#include <exception>

#include "twinslam/trajectory/io.hpp"
#include "twinslam/twin/geo.hpp"

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

std::vector<StampedPoseW> read_truth_tum(const std::string& file) {
  std::vector<StampedPoseW> out;
  for (const StampedPose& p : read_tum(file).poses) {
    const Eigen::Quaterniond q = p.q_XB();
    const Eigen::Vector3d t = p.p_X();
    out.push_back({p.stamp_ns, {{t.x(), t.y(), t.z()}, {q.w(), q.x(), q.y(), q.z()}}});
  }
  return out;
}

DerivedChannels::DerivedChannels(DerivedChannelsConfig config) : config_(config) {}
DerivedChannels::~DerivedChannels() = default;

void DerivedChannels::set_truth(const std::string& vehicle_id, std::vector<StampedPoseW> truth) {
  std::lock_guard lock(mutex_);
  Vehicle& v = vehicles_[vehicle_id];
  v.truth = std::move(truth);
  v.truth_path.clear();
  v.truth_next = 0;
}

void DerivedChannels::set_origin(const std::string& lat_lon_h) {
  auto enu = std::make_unique<twin::EnuFrame>(twin::parse_origin(lat_lon_h));
  std::lock_guard lock(mutex_);
  enu_ = std::move(enu);
}

bool DerivedChannels::append_spaced(std::vector<PoseW>& path, const PoseW& T) const {
  if (!finite(T)) return false;
  if (!path.empty() && distance(path.back(), T) < config_.path_spacing_m) return false;
  if (path.size() >= config_.max_path_poses) {  // every other pose goes: the path keeps its extent, first and last
    std::vector<PoseW> half;
    for (std::size_t i = 0; i < path.size(); i += 2) half.push_back(path[i]);
    path = std::move(half);
  }
  path.push_back(T);
  return true;
}

bool DerivedChannels::advance_truth(Vehicle& v, std::int64_t stamp_ns) const {
  bool grew = false;
  for (; v.truth_next < v.truth.size() && v.truth[v.truth_next].stamp_ns <= stamp_ns; ++v.truth_next) {
    grew = append_spaced(v.truth_path, v.truth[v.truth_next].T_WB) || grew;
  }
  return grew;
}

std::string DerivedChannels::prefix(const std::string& vehicle_id) {
  return "/" + (vehicle_id.empty() ? std::string("unnamed") : vehicle_id);
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::Odometry& m, bool render) {
  const std::string v = prefix(m.vehicle_id());
  std::vector<DerivedMessage> out;
  if (render) out.push_back({v + "/estimate/pose", &pose_in_frame_schema(), pose_json(m), std::nullopt});
  std::lock_guard lock(mutex_);
  Vehicle& vehicle = vehicles_[m.vehicle_id()];
  // The truth is drawn as far as the estimate has come, whether the estimate has a pose yet or not.
  if (advance_truth(vehicle, m.stamp_ns()) && render) {
    out.push_back({v + "/truth/path", &poses_in_frame_schema(), path_json(m.stamp_ns(), vehicle.truth_path),
                   std::nullopt});
  }
  if (m.status() != msg::ODOM_TRACKING && m.status() != msg::ODOM_ALIGNED) return out;  // no pose to draw yet
  if (append_spaced(vehicle.path, pose_of(m.T_WB())) && render) {
    out.push_back({v + "/estimate/path", &poses_in_frame_schema(), path_json(m.stamp_ns(), vehicle.path),
                   std::nullopt});
  }
  return out;
}

std::vector<DerivedMessage> DerivedChannels::on(const msg::GnssFix& m, bool render) {
  const std::string v = prefix(m.vehicle_id());
  std::vector<DerivedMessage> out;
  if (render) out.push_back({v + "/gnss", &location_fix_schema(), location_fix_json(m), std::nullopt});
  std::lock_guard lock(mutex_);
  if (!enu_ || !(std::abs(m.latitude_deg()) <= 90.0) || !(std::abs(m.longitude_deg()) <= 180.0)) return out;
  const Eigen::Vector3d p_W = enu_->from_lla(m.latitude_deg(), m.longitude_deg(), m.altitude_m());
  const PoseW T{{p_W.x(), p_W.y(), p_W.z()}, {1.0, 0.0, 0.0, 0.0}};  // a fix has no orientation
  auto& path = vehicles_[m.vehicle_id()].gnss_path;
  if (append_spaced(path, T) && render) {
    out.push_back({v + "/gnss/path", &poses_in_frame_schema(), path_json(m.stamp_ns(), path), std::nullopt});
  }
  return out;
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

std::vector<DerivedMessage> DerivedChannels::on(const msg::Heartbeat& m, bool /*render*/) {  // latched: always
  return {{"/services", &service_state_schema(), service_state_json(m), m.service() + "@" + m.instance()}};
}

std::uint64_t DerivedChannels::tiles_undecodable() const {
  std::lock_guard lock(mutex_);
  return tiles_undecodable_;
}

}  // namespace twinslam::foxglove
