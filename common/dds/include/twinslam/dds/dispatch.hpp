#pragma once
// Calls f.template operator()<T>() with the message type T of a topic from the table: how generic tools
// (`twinslam topics`, `echo`, the run recorder) subscribe to every topic without a switch of their own.
#include <stdexcept>
#include <string>

#include "twinslam/dds/topics.hpp"
#include "twinslam/dds/types.hpp"

namespace twinslam::dds {

template <class F>
void with_message_type(const TopicSpec& topic, F&& f) {
  const auto& n = topic.type_name;
  if (n == topics::kImu.type_name) return f.template operator()<msg::Imu>();
  if (n == topics::kImage.type_name) return f.template operator()<msg::Image>();
  if (n == topics::kGnss.type_name) return f.template operator()<msg::GnssFix>();
  if (n == topics::kFeatures.type_name) return f.template operator()<msg::FeatureFrame>();
  if (n == topics::kOdometry.type_name) return f.template operator()<msg::Odometry>();
  if (n == topics::kLocalMap.type_name) return f.template operator()<msg::LocalMap>();
  if (n == topics::kRegistration.type_name) return f.template operator()<msg::Registration>();
  if (n == topics::kTileRequest.type_name) return f.template operator()<msg::TileRequest>();
  if (n == topics::kMapTile.type_name) return f.template operator()<msg::MapTile>();
  if (n == topics::kHeartbeat.type_name) return f.template operator()<msg::Heartbeat>();
  if (n == topics::kFrameAck.type_name) return f.template operator()<msg::FrameAck>();
  throw std::logic_error("no message type for topic " + std::string(topic.name));
}

}  // namespace twinslam::dds
