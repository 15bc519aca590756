// Conversions of the pipeline's messages to Foxglove's well-known schemas (well_known.hpp). JSON is built with
// nlohmann::json, whose dump() writes non-finite numbers as null: a NaN in a message cannot make the text invalid.
#include "twinslam/foxglove/well_known.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "twinslam/twin/store.hpp"

namespace twinslam::foxglove {
namespace {

using json = nlohmann::json;

// Strings from the wire (vehicle ids, reasons, tile keys) may hold invalid UTF-8: replaced, never an exception.
std::string text(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

json stamp(std::int64_t ns) {
  if (ns < 0) ns = 0;  // the schema's time is unsigned
  return {{"sec", ns / 1'000'000'000}, {"nsec", ns % 1'000'000'000}};
}

json pose_json_of(const PoseW& T) {
  return {{"position", {{"x", T.p[0]}, {"y", T.p[1]}, {"z", T.p[2]}}},
          {"orientation", {{"x", T.q[1]}, {"y", T.q[2]}, {"z", T.q[3]}, {"w", T.q[0]}}}};
}
const json& identity_pose() {
  static const json identity = pose_json_of(PoseW{{0, 0, 0}, {1, 0, 0, 0}});
  return identity;
}

Eigen::Isometry3d isometry(const msg::Pose& T) {
  Eigen::Quaterniond q(T.q().w(), T.q().x(), T.q().y(), T.q().z());
  // A zero or non-finite quaternion stays as it is (its NaNs become nulls), never a division by zero.
  if (q.norm() > 0) q.normalize();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = q.toRotationMatrix();
  out.translation() = Eigen::Vector3d(T.p().x(), T.p().y(), T.p().z());
  return out;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = static_cast<std::uint32_t>(bytes[i]) << 16;
    if (n > 1) v |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
    if (n > 2) v |= bytes[i + 2];
    for (std::size_t k = 0; k < 4; ++k) out.push_back(k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=');
  }
  return out;
}

void put_float(std::vector<std::uint8_t>& out, double value) {
  const float f = static_cast<float>(value);
  std::uint8_t b[4];
  std::memcpy(b, &f, 4);  // little endian on every target this builds for (x86-64, arm64)
  out.insert(out.end(), b, b + 4);
}

}  // namespace

PoseW pose_of(const msg::Pose& T) {
  return {{T.p().x(), T.p().y(), T.p().z()}, {T.q().w(), T.q().x(), T.q().y(), T.q().z()}};
}

std::string pose_json(const msg::Odometry& m) {
  return text(json{{"timestamp", stamp(m.stamp_ns())},
                   {"frame_id", kWorldFrame},
                   {"pose", pose_json_of(pose_of(m.T_WB()))}});
}

std::string path_json(std::int64_t stamp_ns, const std::vector<PoseW>& path) {
  json poses = json::array();
  for (const PoseW& T : path) poses.push_back(pose_json_of(T));
  return text(json{{"timestamp", stamp(stamp_ns)}, {"frame_id", kWorldFrame}, {"poses", std::move(poses)}});
}

std::string location_fix_json(const msg::GnssFix& m) {
  json cov = json::array();
  for (double c : m.covariance_enu_m2()) cov.push_back(c);
  return text(json{{"timestamp", stamp(m.stamp_ns())},
              {"frame_id", m.vehicle_id().empty() ? std::string("gnss") : m.vehicle_id() + "/gnss"},
              {"latitude", m.latitude_deg()},
              {"longitude", m.longitude_deg()},
              {"altitude", m.altitude_m()},
              {"position_covariance", std::move(cov)},
              {"position_covariance_type", 3}});  // KNOWN: the full ENU matrix
}

std::string landmarks_json(const msg::LocalMap& m, const msg::Pose* correction_W) {
  const Eigen::Isometry3d T_WL =
      (correction_W ? isometry(*correction_W) : Eigen::Isometry3d::Identity()) * isometry(m.T_WL());
  std::vector<std::uint8_t> data;
  data.reserve(m.landmarks().size() * 16);
  for (const msg::Landmark& l : m.landmarks()) {
    const Eigen::Vector3d p_W = T_WL * Eigen::Vector3d(l.p_L().x(), l.p_L().y(), l.p_L().z());
    for (int k = 0; k < 3; ++k) put_float(data, p_W[k]);
    put_float(data, l.quality());
  }
  json fields = json::array();
  int offset = 0;
  for (const char* name : {"x", "y", "z", "quality"}) {
    fields.push_back({{"name", name}, {"offset", offset}, {"type", 7}});  // 7: FLOAT32
    offset += 4;
  }
  return text(json{{"timestamp", stamp(m.keyframe_stamp_ns())}, {"frame_id", kWorldFrame}, {"pose", identity_pose()},
              {"point_stride", 16}, {"fields", std::move(fields)}, {"data", base64(data)}});
}

std::string tile_scene_json(const msg::MapTile& m) {
  const twin::Mesh mesh = m.mesh_draco().empty()
                              ? twin::Mesh{}
                              : twin::decode_draco(m.mesh_draco().data(), m.mesh_draco().size(),
                                                   "map tile " + m.tile_key());
  json points = json::array();
  for (const Eigen::Vector3d& p : mesh.p_W) points.push_back({{"x", p.x()}, {"y", p.y()}, {"z", p.z()}});
  json indices = json::array();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) indices.push_back(t[k]);
  }
  json triangles = json::array();
  if (!mesh.triangles.empty()) {
    triangles.push_back({{"pose", identity_pose()}, {"points", std::move(points)},
                         {"color", {{"r", 0.62}, {"g", 0.66}, {"b", 0.72}, {"a", 0.85}}},  // light grey buildings
                         {"colors", json::array()}, {"indices", std::move(indices)}});
  }
  json entity = {{"timestamp", stamp(0)}, {"frame_id", kWorldFrame}, {"id", "tile/" + m.tile_key()},
                 {"lifetime", {{"sec", 0}, {"nsec", 0}}},  // until replaced
                 {"frame_locked", true}, {"metadata", json::array({{{"key", "twin_id"}, {"value", m.twin_id()}}})},
                 {"triangles", std::move(triangles)}};
  for (const char* kind : {"arrows", "cubes", "spheres", "cylinders", "lines", "texts", "models"}) {
    entity[kind] = json::array();
  }
  return text(json{{"deletions", json::array()}, {"entities", json::array({std::move(entity)})}});
}

std::string_view registration_status_name(msg::RegistrationStatus s) {
  switch (s) {
    case msg::REG_ACCEPTED: return "ACCEPTED";
    case msg::REG_REJECTED_FEW_POINTS: return "REJECTED_FEW_POINTS";
    case msg::REG_REJECTED_NOT_CONVERGED: return "REJECTED_NOT_CONVERGED";
    case msg::REG_REJECTED_DEGENERATE: return "REJECTED_DEGENERATE";
    case msg::REG_REJECTED_NO_MAP: return "REJECTED_NO_MAP";
    case msg::REG_REJECTED_FEW_INLIERS: return "REJECTED_FEW_INLIERS";
    case msg::REG_REJECTED_FITNESS: return "REJECTED_FITNESS";
    case msg::REG_REJECTED_RMSE: return "REJECTED_RMSE";
    case msg::REG_REJECTED_CORRECTION: return "REJECTED_CORRECTION";
  }
  return "UNKNOWN";  // a value outside the enum (a newer sender)
}

std::string registration_health_json(const msg::Registration& m) {
  const Eigen::Isometry3d dT = isometry(m.correction_W());
  const double angle = Eigen::AngleAxisd(dT.linear()).angle();
  json eigen = json::array();
  for (double e : m.information_eigenvalues()) eigen.push_back(e);
  return text(json{{"timestamp", stamp(m.keyframe_stamp_ns())},
              {"vehicle_id", m.vehicle_id()},
              {"status", registration_status_name(m.status())},
              {"accepted", m.status() == msg::REG_ACCEPTED},
              {"reason", m.reason()},
              {"rmse_m", m.rmse_m()},
              {"source_points", m.source_points()},
              {"inliers", m.inliers()},
              {"fitness", m.fitness()},
              {"information_eigenvalues", std::move(eigen)},
              {"correction_translation_m", dT.translation().norm()},
              {"correction_rotation_deg", angle * 180.0 / M_PI},
              {"compute_ms", m.compute_ms()},
              {"latency_ms", m.latency_ms()},
              {"readmitted", m.readmitted()}});
}

std::string_view service_state_name(msg::ServiceState s) {
  switch (s) {
    case msg::SVC_STARTING: return "STARTING";
    case msg::SVC_READY: return "READY";
    case msg::SVC_RUNNING: return "RUNNING";
    case msg::SVC_DONE: return "DONE";
    case msg::SVC_STOPPING: return "STOPPING";
    case msg::SVC_FAILED: return "FAILED";
  }
  return "UNKNOWN";
}

std::string service_state_json(const msg::Heartbeat& m) {
  json counters = json::array();
  for (const msg::Counter& c : m.counters()) counters.push_back({{"name", c.name()}, {"value", c.value()}});
  return text(json{{"timestamp", stamp(m.wall_ns())},
                   {"service", m.service()},
                   {"instance", m.instance()},
                   {"vehicle_id", m.vehicle_id()},
                   {"state", service_state_name(m.state())},
                   {"uptime_ms", m.uptime_ms()},
                   {"counters", std::move(counters)}});
}

}  // namespace twinslam::foxglove
