#pragma once
// Template bodies of node.hpp that need the full DataReader API.
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace twinslam::dds {

template <class T>
void CallbackListener<T>::on_data_available(eprosima::fastdds::dds::DataReader* reader) {
  // Take everything available now: with KEEP_ALL readers an unread sample holds back the lockstep writer.
  T sample;
  eprosima::fastdds::dds::SampleInfo info;
  while (reader->take_next_sample(&sample, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    status.received.fetch_add(1);
    cb_(sample);
  }
}

}  // namespace twinslam::dds
