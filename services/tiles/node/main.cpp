// twinslam-tiles: streams the digital twin's tiles around each vehicle
#include "tiles_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam tiles service: streams the digital twin's tiles around each vehicle"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  return twinslam::dds::service_main("tiles", app, service, argc, argv, [&] {
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::tiles::wire_tiles_inputs(node, counters);
    return twinslam::dds::serve_until_shutdown(heartbeat);
  });
}
