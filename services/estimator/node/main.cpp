// twinslam-estimator: sliding-window visual-inertial estimator (features + IMU in, odometry and local maps out)
#include "estimator_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam estimator service: sliding-window visual-inertial estimator (features + IMU in, odometry and local maps out)"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  return twinslam::dds::service_main("estimator", app, service, argc, argv, [&] {
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::estimator::wire_estimator_inputs(node, counters);
    return twinslam::dds::serve_until_shutdown(heartbeat);
  });
}
