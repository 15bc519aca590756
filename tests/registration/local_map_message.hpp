#pragma once
// A LocalMap message of a registration source (the estimator's view), as the estimator publishes it.
#include <cstdint>
#include <string>

#include "twinslam/dds/convert.hpp"
#include "twinslam/registration/preprocess.hpp"

namespace twinslam::registration::test {

inline msg::LocalMap local_map(const std::string& vehicle, std::int64_t stamp_ns, const SourceInput& src) {
  msg::LocalMap lm;
  lm.vehicle_id(vehicle);
  lm.keyframe_stamp_ns(stamp_ns);
  lm.T_LB(dds::to_msg(src.T_LB));
  lm.T_WL(dds::to_msg(src.T_WL));
  for (const auto& l : src.landmarks) {
    msg::Landmark x;
    x.p_L(dds::to_msg(l.p_L));
    x.quality(1.0f);
    lm.landmarks().push_back(x);
  }
  return lm;
}

}  // namespace twinslam::registration::test
