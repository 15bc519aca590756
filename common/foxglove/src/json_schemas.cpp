// JSON Schemas of the channels the bridge and the MCAP recorder advertise (schemaEncoding "jsonschema"). Foxglove
// recognizes the foxglove.* names and draws them; the schema text gives field types to its Plot panel and to any
// generic JSON consumer. Written from the schema reference (foxglove.dev/docs/visualization/message-schemas) for the
// fields this project fills; tests/node/bridge_client.mjs checks the messages against @foxglove/schemas' own.
#include <nlohmann/json.hpp>

#include "twinslam/foxglove/well_known.hpp"

namespace twinslam::foxglove {
namespace {

using json = nlohmann::json;

json object(std::string title, json properties) {
  json required = json::array();
  for (const auto& [key, value] : properties.items()) required.push_back(key);
  return {{"title", std::move(title)}, {"type", "object"}, {"properties", std::move(properties)},
          {"required", std::move(required)}};
}
json number() { return {{"type", "number"}}; }
json integer(int minimum) { return {{"type", "integer"}, {"minimum", minimum}}; }
json string() { return {{"type", "string"}}; }
json array_of(json items) { return {{"type", "array"}, {"items", std::move(items)}}; }
json time() { return object("time", {{"sec", integer(0)}, {"nsec", integer(0)}}); }
json xyz(std::string title) { return object(std::move(title), {{"x", number()}, {"y", number()}, {"z", number()}}); }
json pose() {
  return object("foxglove.Pose", {{"position", xyz("foxglove.Vector3")},
                                  {"orientation", object("foxglove.Quaternion", {{"x", number()}, {"y", number()},
                                                                                 {"z", number()}, {"w", number()}})}});
}
json color() { return object("foxglove.Color", {{"r", number()}, {"g", number()}, {"b", number()}, {"a", number()}}); }

json scene_entity() {
  json triangles = object("foxglove.TriangleListPrimitive",
                          {{"pose", pose()}, {"points", array_of(xyz("foxglove.Point3"))}, {"color", color()},
                           {"colors", array_of(color())}, {"indices", array_of(integer(0))}});
  json e = object("foxglove.SceneEntity",
                  {{"timestamp", time()}, {"frame_id", string()}, {"id", string()},
                   {"lifetime", object("duration", {{"sec", integer(0)}, {"nsec", integer(0)}})},
                   {"frame_locked", {{"type", "boolean"}}},
                   {"metadata", array_of(object("foxglove.KeyValuePair", {{"key", string()}, {"value", string()}}))},
                   {"triangles", array_of(std::move(triangles))}});
  // Primitive kinds this project never fills: arrays of objects all the same (required by the schema).
  for (const char* kind : {"arrows", "cubes", "spheres", "cylinders", "lines", "texts", "models"}) {
    e["properties"][kind] = array_of({{"type", "object"}});
    e["required"].push_back(kind);
  }
  return e;
}

std::string text(const json& j) { return j.dump(); }

}  // namespace

const Schema& pose_in_frame_schema() {
  static const std::string s =
      text(object("foxglove.PoseInFrame", {{"timestamp", time()}, {"frame_id", string()}, {"pose", pose()}}));
  static const Schema schema{"foxglove.PoseInFrame", s};
  return schema;
}

const Schema& poses_in_frame_schema() {
  static const std::string s = text(
      object("foxglove.PosesInFrame", {{"timestamp", time()}, {"frame_id", string()}, {"poses", array_of(pose())}}));
  static const Schema schema{"foxglove.PosesInFrame", s};
  return schema;
}

const Schema& location_fix_schema() {
  static const std::string s = text(object(
      "foxglove.LocationFix",
      {{"timestamp", time()}, {"frame_id", string()}, {"latitude", number()}, {"longitude", number()},
       {"altitude", number()},
       {"position_covariance", {{"type", "array"}, {"items", number()}, {"minItems", 9}, {"maxItems", 9}}},
       {"position_covariance_type", integer(0)}}));
  static const Schema schema{"foxglove.LocationFix", s};
  return schema;
}

const Schema& point_cloud_schema() {
  static const std::string s = text(object(
      "foxglove.PointCloud",
      {{"timestamp", time()}, {"frame_id", string()}, {"pose", pose()}, {"point_stride", integer(0)},
       {"fields", array_of(object("foxglove.PackedElementField",
                                  {{"name", string()}, {"offset", integer(0)}, {"type", integer(0)}}))},
       {"data", {{"type", "string"}, {"contentEncoding", "base64"}}}}));
  static const Schema schema{"foxglove.PointCloud", s};
  return schema;
}

const Schema& scene_update_schema() {
  static const std::string s = text(object(
      "foxglove.SceneUpdate",
      {{"deletions", array_of(object("foxglove.SceneEntityDeletion",
                                     {{"timestamp", time()}, {"type", integer(0)}, {"id", string()}}))},
       {"entities", array_of(scene_entity())}}));
  static const Schema schema{"foxglove.SceneUpdate", s};
  return schema;
}

const Schema& registration_health_schema() {
  static const std::string s = text(object(
      "twinslam.RegistrationHealth",
      {{"timestamp", time()}, {"vehicle_id", string()}, {"status", string()}, {"accepted", {{"type", "boolean"}}},
       {"reason", string()}, {"rmse_m", number()}, {"source_points", integer(0)}, {"inliers", integer(0)},
       {"fitness", number()}, {"information_eigenvalues", array_of(number())},
       {"correction_translation_m", number()}, {"correction_rotation_deg", number()}, {"compute_ms", number()},
       {"latency_ms", number()}, {"readmitted", {{"type", "boolean"}}}}));
  static const Schema schema{"twinslam.RegistrationHealth", s};
  return schema;
}

const Schema& service_state_schema() {
  static const std::string s = text(object(
      "twinslam.ServiceState",
      {{"timestamp", time()}, {"service", string()}, {"instance", string()}, {"vehicle_id", string()},
       {"state", string()}, {"uptime_ms", integer(0)},
       {"counters", array_of(object("twinslam.Counter", {{"name", string()}, {"value", integer(0)}}))}}));
  static const Schema schema{"twinslam.ServiceState", s};
  return schema;
}

}  // namespace twinslam::foxglove
