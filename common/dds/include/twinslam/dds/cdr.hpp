#pragma once
// A message as the bytes DDS puts on the wire: the 4-byte encapsulation header (CDR little endian, XCDR1 as Fast
// DDS 2.9's generated types write it) followed by the CDR body. This is the "cdr" message encoding of MCAP and of
// Foxglove's WebSocket protocol, whose readers decode it with the IDL of twinslam/IdlText.h (schema encoding
// "omgidl", schema name = the type's fully qualified IDL name, e.g. twinslam::msg::Odometry).
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "twinslam/dds/types.hpp"

namespace twinslam::dds {

template <class T>
std::vector<std::uint8_t> to_cdr(const T& m) {
  typename PubSubTypeOf<T>::type type;
  T& data = const_cast<T&>(m);  // the generated API takes void*; serialize only reads it
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&data)());
  if (!type.serialize(&data, &payload)) throw std::runtime_error("CDR serialization failed");
  return {payload.data, payload.data + payload.length};
}

}  // namespace twinslam::dds
