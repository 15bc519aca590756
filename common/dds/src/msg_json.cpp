#include "twinslam/dds/msg_json.hpp"

#include <nlohmann/json.hpp>

namespace twinslam::dds {
unsigned long long fnv1a64(const unsigned char* data, std::size_t size) {
  unsigned long long h = 1469598103934665603ULL;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ULL;
  return h;
}

const char* to_string(msg::ServiceState s) {
  switch (s) {
    case msg::SVC_STARTING: return "starting";
    case msg::SVC_READY: return "ready";
    case msg::SVC_RUNNING: return "running";
    case msg::SVC_DONE: return "done";
    case msg::SVC_STOPPING: return "stopping";
    case msg::SVC_FAILED: return "failed";
  }
  return "unknown";
}
}  // namespace twinslam::dds

namespace twinslam::msg {
using nlohmann::json;

namespace {
json blob(const std::vector<uint8_t>& bytes) {
  return {{"bytes", bytes.size()}, {"fnv1a64", twinslam::dds::fnv1a64(bytes.data(), bytes.size())}};
}
template <std::size_t N>
json array(const std::array<double, N>& a) {
  return json(std::vector<double>(a.begin(), a.end()));
}
}  // namespace

void to_json(json& j, const Vec3& m) { j = json::array({m.x(), m.y(), m.z()}); }
void to_json(json& j, const Quat& m) { j = json::array({m.w(), m.x(), m.y(), m.z()}); }
void to_json(json& j, const Pose& m) { j = {{"q_wxyz", m.q()}, {"p", m.p()}}; }

void to_json(json& j, const Imu& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"stamp_ns", m.stamp_ns()}, {"seq", m.seq()},
       {"gyro_radps", m.gyro_radps()}, {"accel_mps2", m.accel_mps2()}};
}
void to_json(json& j, const Image& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"camera_id", m.camera_id()}, {"stamp_ns", m.stamp_ns()},
       {"seq", m.seq()}, {"width", m.width()}, {"height", m.height()}, {"step", m.step()},
       {"encoding", m.encoding()}, {"data", blob(m.data())}};
}
void to_json(json& j, const GnssFix& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"stamp_ns", m.stamp_ns()}, {"seq", m.seq()},
       {"latitude_deg", m.latitude_deg()}, {"longitude_deg", m.longitude_deg()}, {"altitude_m", m.altitude_m()},
       {"covariance_enu_m2", array(m.covariance_enu_m2())}, {"num_satellites", m.num_satellites()}};
}
void to_json(json& j, const FeatureFrame& m) {
  json features = json::array();
  for (const auto& f : m.features()) {
    features.push_back({{"id", f.id()}, {"uv", {f.u(), f.v()}}, {"bearing_C", f.bearing_C()},
                        {"track_length", f.track_length()}});
  }
  j = {{"vehicle_id", m.vehicle_id()}, {"camera_id", m.camera_id()}, {"stamp_ns", m.stamp_ns()},
       {"seq", m.seq()}, {"tracking_ms", m.tracking_ms()}, {"features", features}};
}
void to_json(json& j, const Odometry& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"stamp_ns", m.stamp_ns()}, {"seq", m.seq()},
       {"status", static_cast<int>(m.status())}, {"T_LB", m.T_LB()}, {"T_WL", m.T_WL()}, {"T_WB", m.T_WB()},
       {"v_L", m.v_L()}, {"bias_gyro", m.bias_gyro()}, {"bias_accel", m.bias_accel()},
       {"estimator_ms", m.estimator_ms()}};
}
void to_json(json& j, const LocalMap& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"keyframe_stamp_ns", m.keyframe_stamp_ns()}, {"seq", m.seq()},
       {"T_LB", m.T_LB()}, {"T_WL", m.T_WL()}, {"landmarks", m.landmarks().size()}};
}
void to_json(json& j, const Registration& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"keyframe_stamp_ns", m.keyframe_stamp_ns()}, {"seq", m.seq()},
       {"status", static_cast<int>(m.status())}, {"reason", m.reason()}, {"correction_W", m.correction_W()},
       {"pivot_W", m.pivot_W()}, {"information", array(m.information())},
       {"information_eigenvalues", array(m.information_eigenvalues())}, {"rmse_m", m.rmse_m()},
       {"source_points", m.source_points()}, {"inliers", m.inliers()}, {"fitness", m.fitness()},
       {"compute_ms", m.compute_ms()}, {"latency_ms", m.latency_ms()}};
}
void to_json(json& j, const TileRequest& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"stamp_ns", m.stamp_ns()}, {"center_e_m", m.center_e_m()},
       {"center_n_m", m.center_n_m()}, {"half_size_m", m.half_size_m()}, {"have", m.have()}};
}
void to_json(json& j, const MapTile& m) {
  j = {{"tile_key", m.tile_key()}, {"twin_id", m.twin_id()}, {"bounds_W", array(m.bounds_W())},
       {"triangles", m.triangles()}, {"points", m.points()}, {"mesh_draco", blob(m.mesh_draco())},
       {"points_draco", blob(m.points_draco())}};
}
void to_json(json& j, const Heartbeat& m) {
  json counters = json::object();
  for (const auto& c : m.counters()) counters[c.name()] = c.value();
  j = {{"service", m.service()}, {"instance", m.instance()}, {"vehicle_id", m.vehicle_id()},
       {"state", twinslam::dds::to_string(m.state())}, {"uptime_ms", m.uptime_ms()}, {"counters", counters}};
}
void to_json(json& j, const FrameAck& m) {
  j = {{"vehicle_id", m.vehicle_id()}, {"service", m.service()}, {"stamp_ns", m.stamp_ns()}, {"seq", m.seq()}};
}
}  // namespace twinslam::msg
