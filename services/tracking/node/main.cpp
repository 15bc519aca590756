// twinslam-tracking: visual frontend service (images -> FeatureFrame).
#include "tracking_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam tracking service: images and IMU in, tracked features out"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  return twinslam::dds::service_main("tracking", app, service, argc, argv, [&] {
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::tracking::TrackingNode tracking(node, counters);
    return twinslam::dds::serve_until_shutdown(heartbeat);
  });
}
