// twinslam-estimator: sliding-window visual-inertial estimator (features + IMU in, odometry and local maps out)
#include "estimator_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  return twinslam::dds::run_wired_service(
      "estimator", "twinslam estimator service: sliding-window visual-inertial estimator (features + IMU in, odometry and local maps out)",
      argc, argv, twinslam::estimator::wire_estimator_inputs);
}
