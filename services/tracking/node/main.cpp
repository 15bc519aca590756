// twinslam-tracking: visual frontend service (images -> FeatureFrame).
#include <memory>

#include "tracking_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  std::unique_ptr<twinslam::tracking::TrackingNode> tracking;
  return twinslam::dds::run_wired_service(
      "tracking", "twinslam tracking service: images and IMU in, tracked features out", argc, argv,
      [&](twinslam::dds::Node& node, twinslam::dds::Counters& counters) {
        tracking = std::make_unique<twinslam::tracking::TrackingNode>(node, counters);
      });
}
