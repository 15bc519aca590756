// twinslam-tiles: streams the digital twin's tiles around each vehicle (odometry / GNSS / tile requests in, MapTile out).
#include "tiles_node.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam tiles service: streams the digital twin's tiles around each vehicle"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  std::string twin_dir, config_file;
  app.add_option("--twin", twin_dir, "Twin store folder (`twinslam twin build` output); required unless --config "
                                     "names twin_dir, and wins over it");
  app.add_option("--config", config_file, "Tiles config YAML: window_m, cache_tiles, twin_dir");
  return twinslam::dds::service_main("tiles", app, service, argc, argv, [&] {
    // The node first, so a bad QoS file or profile is reported as such whatever else is missing.
    twinslam::dds::Node node(service.node);
    twinslam::tiles::TilesConfig config;
    if (!config_file.empty()) config = twinslam::tiles::load_tiles_config(config_file);
    if (!twin_dir.empty()) config.twin_dir = twin_dir;
    if (config.twin_dir.empty()) throw twinslam::UsageError("--twin TWIN_DIR (or twin_dir in --config) is required");
    config.validate(config_file.empty() ? "command line" : config_file);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::tiles::TilesNode tiles(node, counters, config);
    return twinslam::dds::serve_until_shutdown(heartbeat, node);
  });
}
