// twinslam-registration: aligns each vehicle's local map to the digital twin
#include "registration_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam registration service: aligns each vehicle's local map to the digital twin"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  return twinslam::dds::service_main("registration", app, service, argc, argv, [&] {
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::registration::wire_registration_inputs(node, counters);
    return twinslam::dds::serve_until_shutdown(heartbeat);
  });
}
