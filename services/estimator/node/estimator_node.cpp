#include "estimator_node.hpp"

namespace twinslam::estimator {

void wire_estimator_inputs(dds::Node& node, dds::Counters& counters) {
  node.subscribe<msg::FeatureFrame>(dds::topics::kFeatures, [&counters](const msg::FeatureFrame&) { counters.add("features_in"); });
  node.subscribe<msg::Imu>(dds::topics::kImu, [&counters](const msg::Imu&) { counters.add("imu_in"); });
  node.subscribe<msg::GnssFix>(dds::topics::kGnss, [&counters](const msg::GnssFix&) { counters.add("gnss_in"); });
  node.subscribe<msg::Registration>(dds::topics::kRegistration, [&counters](const msg::Registration&) { counters.add("registrations_in"); });
}

}  // namespace twinslam::estimator
