#pragma once
// Maps each generated message type to its generated PubSubType, so Node::writer<T>() needs only T.
#include <twinslam/BenchPubSubTypes.h>
#include <twinslam/EstimationPubSubTypes.h>
#include <twinslam/MapPubSubTypes.h>
#include <twinslam/RegistrationPubSubTypes.h>
#include <twinslam/SensorsPubSubTypes.h>
#include <twinslam/SystemPubSubTypes.h>
#include <twinslam/VisionPubSubTypes.h>

namespace twinslam::dds {

template <class T>
struct PubSubTypeOf;

#define TWINSLAM_DDS_TYPE(T)         \
  template <>                        \
  struct PubSubTypeOf<msg::T> {      \
    using type = msg::T##PubSubType; \
  };
TWINSLAM_DDS_TYPE(Imu)
TWINSLAM_DDS_TYPE(Image)
TWINSLAM_DDS_TYPE(GnssFix)
TWINSLAM_DDS_TYPE(FeatureFrame)
TWINSLAM_DDS_TYPE(Odometry)
TWINSLAM_DDS_TYPE(LocalMap)
TWINSLAM_DDS_TYPE(Registration)
TWINSLAM_DDS_TYPE(TileRequest)
TWINSLAM_DDS_TYPE(MapTile)
TWINSLAM_DDS_TYPE(Heartbeat)
TWINSLAM_DDS_TYPE(FrameAck)
TWINSLAM_DDS_TYPE(Ping)
#undef TWINSLAM_DDS_TYPE

}  // namespace twinslam::dds
