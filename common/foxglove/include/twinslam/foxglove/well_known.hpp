#pragma once
// The pipeline's messages in Foxglove's well-known schemas (foxglove.dev/docs/visualization/message-schemas), JSON
// encoding: what Foxglove's 3D, Map and Plot panels draw without knowing this project. Every function is pure and
// total: any message gives valid JSON (a non-finite number becomes null, a negative stamp 0 s). Frame ids: "world" is
// W (ENU at the dataset origin, metres); everything is drawn in W.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <twinslam/Estimation.h>
#include <twinslam/Map.h>
#include <twinslam/Registration.h>
#include <twinslam/Sensors.h>
#include <twinslam/System.h>

namespace twinslam::foxglove {

inline constexpr std::string_view kWorldFrame = "world";

// A channel's schema: its name (Foxglove recognizes the foxglove.* ones) and JSON Schema text.
struct Schema {
  std::string_view name;
  std::string_view jsonschema;
};
const Schema& pose_in_frame_schema();         // foxglove.PoseInFrame
const Schema& poses_in_frame_schema();        // foxglove.PosesInFrame
const Schema& location_fix_schema();          // foxglove.LocationFix
const Schema& point_cloud_schema();           // foxglove.PointCloud
const Schema& scene_update_schema();          // foxglove.SceneUpdate
const Schema& registration_health_schema();   // twinslam.RegistrationHealth (this project's, for the Plot panel)
const Schema& service_state_schema();         // twinslam.ServiceState (this project's: a service's heartbeat)

struct PoseW {  // a pose in W: position [m], orientation quaternion (w, x, y, z)
  double p[3];
  double q[4];
};
PoseW pose_of(const msg::Pose& T);

// foxglove.PoseInFrame: the body pose T_WB of an estimate.
std::string pose_json(const msg::Odometry& m);
// foxglove.PosesInFrame: a path in W stamped at `stamp_ns`.
std::string path_json(std::int64_t stamp_ns, const std::vector<PoseW>& path);
// foxglove.LocationFix: a GNSS fix (WGS84, ENU covariance; type KNOWN).
std::string location_fix_json(const msg::GnssFix& m);
// foxglove.PointCloud: landmarks p_W = T_WL_eff * p_L with fields x, y, z, quality (float32, stride 16), where
// T_WL_eff = correction_W * T_WL (no correction: the cloud as the estimator places it; a registration's: as the twin
// places it, eq. 3).
std::string landmarks_json(const msg::LocalMap& m, const msg::Pose* correction_W = nullptr);
// foxglove.SceneUpdate: one entity "tile/<tile_key>" holding the tile's triangles in W (decoded from its Draco mesh);
// a tile without triangles gives an entity with none. Throws InputError naming the tile if its mesh does not decode.
std::string tile_scene_json(const msg::MapTile& m);
// twinslam.RegistrationHealth: status, RMSE, inliers, fitness, information eigenvalues, the correction's size, times.
std::string registration_health_json(const msg::Registration& m);

// twinslam.ServiceState: a heartbeat — service, instance, vehicle, state, uptime, counters; stamped with the
// sender's wall clock (display only).
std::string service_state_json(const msg::Heartbeat& m);

// The IDL status's name without its prefix, e.g. "ACCEPTED", "REJECTED_RMSE".
std::string_view registration_status_name(msg::RegistrationStatus s);
// The service state's name without its prefix, e.g. "RUNNING".
std::string_view service_state_name(msg::ServiceState s);

}  // namespace twinslam::foxglove
