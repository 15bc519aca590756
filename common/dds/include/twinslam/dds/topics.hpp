#pragma once
// The topic contract of twinslam: names, types and the QoS profile family of each topic. idl/README.md documents the
// same table for people; this file is the one code reads. Names carry a version ("v1"): IDL types are plain CDR in
// Fast DDS 2.9 (no type evolution), so a changed type gets a new topic version instead of breaking old peers.
#include <array>
#include <string_view>

namespace twinslam::dds {

// Which QoS profile pair of deploy/qos/twinslam.xml a topic uses (see the comments there for the why).
enum class QosFamily { Sensor, Result, Tile, Control, Heartbeat };

struct TopicSpec {
  std::string_view name;
  std::string_view type_name;  // as registered by the generated PubSubType
  QosFamily family;
};

namespace topics {
inline constexpr TopicSpec kImu{"twinslam/v1/imu", "twinslam::msg::Imu", QosFamily::Sensor};
inline constexpr TopicSpec kImage{"twinslam/v1/image", "twinslam::msg::Image", QosFamily::Sensor};
inline constexpr TopicSpec kGnss{"twinslam/v1/gnss", "twinslam::msg::GnssFix", QosFamily::Sensor};
inline constexpr TopicSpec kFeatures{"twinslam/v1/features", "twinslam::msg::FeatureFrame", QosFamily::Result};
inline constexpr TopicSpec kOdometry{"twinslam/v2/odometry", "twinslam::msg::Odometry", QosFamily::Result};
inline constexpr TopicSpec kLocalMap{"twinslam/v2/local_map", "twinslam::msg::LocalMap", QosFamily::Result};
inline constexpr TopicSpec kRegistration{"twinslam/v3/registration", "twinslam::msg::Registration", QosFamily::Result};
inline constexpr TopicSpec kTileRequest{"twinslam/v1/tile_request", "twinslam::msg::TileRequest", QosFamily::Control};
inline constexpr TopicSpec kMapTile{"twinslam/v1/map_tile", "twinslam::msg::MapTile", QosFamily::Tile};
inline constexpr TopicSpec kHeartbeat{"twinslam/v1/heartbeat", "twinslam::msg::Heartbeat", QosFamily::Heartbeat};
inline constexpr TopicSpec kFrameAck{"twinslam/v1/frame_ack", "twinslam::msg::FrameAck", QosFamily::Control};

inline constexpr std::array kAll{kImu,      kImage,       kGnss,    kFeatures,  kOdometry, kLocalMap,
                                 kRegistration, kTileRequest, kMapTile, kHeartbeat, kFrameAck};
}  // namespace topics

// Replay mode of the sensor streams: live pacing or lossless lockstep (CONTRACTS.md --realtime / --max).
enum class Replay { Realtime, Lockstep };

// Profile names in deploy/qos/twinslam.xml.
std::string_view writer_profile(QosFamily family, Replay replay);
std::string_view reader_profile(QosFamily family);
inline constexpr std::string_view kMonitorReaderProfile = "monitor.reader";

// Finds a topic by name (with or without the "twinslam/v1/" prefix); nullptr if unknown.
const TopicSpec* find_topic(std::string_view name);

}  // namespace twinslam::dds
