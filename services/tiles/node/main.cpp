// twinslam-tiles: streams the digital twin's tiles around each vehicle
#include "tiles_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  return twinslam::dds::run_wired_service(
      "tiles", "twinslam tiles service: streams the digital twin's tiles around each vehicle",
      argc, argv, twinslam::tiles::wire_tiles_inputs);
}
