// twinslam-registration: aligns each vehicle's local map to the digital twin
#include "registration_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  return twinslam::dds::run_wired_service(
      "registration", "twinslam registration service: aligns each vehicle's local map to the digital twin",
      argc, argv, twinslam::registration::wire_registration_inputs);
}
