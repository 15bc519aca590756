#include "twinslam/dds/topics.hpp"

namespace twinslam::dds {

std::string_view writer_profile(QosFamily family, Replay replay) {
  switch (family) {
    case QosFamily::Sensor:
      return replay == Replay::Lockstep ? "sensor.lockstep.writer" : "sensor.realtime.writer";
    case QosFamily::Result: return "result.writer";
    case QosFamily::Tile: return "tile.writer";
    case QosFamily::Control: return "control.writer";
    case QosFamily::Heartbeat: return "heartbeat.writer";
  }
  return "result.writer";
}

std::string_view reader_profile(QosFamily family) {
  switch (family) {
    case QosFamily::Sensor: return "sensor.reader";
    case QosFamily::Result: return "result.reader";
    case QosFamily::Tile: return "tile.reader";
    case QosFamily::Control: return "control.reader";
    case QosFamily::Heartbeat: return "heartbeat.reader";
  }
  return "result.reader";
}

const TopicSpec* find_topic(std::string_view name) {
  for (const auto& t : topics::kAll) {
    if (t.name == name) return &t;
    const auto slash = t.name.rfind('/');
    if (t.name.substr(slash + 1) == name) return &t;
  }
  return nullptr;
}

}  // namespace twinslam::dds
