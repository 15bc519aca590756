#pragma once
// Human/JSON view of every message type, for `twinslam echo` and logs. Bulk payloads (pixels, Draco bytes) are
// summarized by size and a 64-bit FNV-1a checksum instead of printed.
#include <nlohmann/json_fwd.hpp>

#include "twinslam/dds/types.hpp"

namespace twinslam::msg {
void to_json(nlohmann::json& j, const Vec3& m);
void to_json(nlohmann::json& j, const Quat& m);
void to_json(nlohmann::json& j, const Pose& m);
void to_json(nlohmann::json& j, const Imu& m);
void to_json(nlohmann::json& j, const Image& m);
void to_json(nlohmann::json& j, const GnssFix& m);
void to_json(nlohmann::json& j, const FeatureFrame& m);
void to_json(nlohmann::json& j, const Odometry& m);
void to_json(nlohmann::json& j, const LocalMap& m);
void to_json(nlohmann::json& j, const Registration& m);
void to_json(nlohmann::json& j, const TileRequest& m);
void to_json(nlohmann::json& j, const MapTile& m);
void to_json(nlohmann::json& j, const Heartbeat& m);
void to_json(nlohmann::json& j, const FrameAck& m);
}  // namespace twinslam::msg

namespace twinslam::dds {
unsigned long long fnv1a64(const unsigned char* data, std::size_t size);
const char* to_string(msg::ServiceState s);
}  // namespace twinslam::dds
