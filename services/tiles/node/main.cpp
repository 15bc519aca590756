// twinslam-tiles: streams the digital twin's tiles around each vehicle (odometry, GNSS, tile requests in; MapTile out).
#include <spdlog/spdlog.h>

#include "tiles_node.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  namespace dds = twinslam::dds;
  CLI::App app{"twinslam tiles service: streams the digital twin's tiles around each vehicle"};
  dds::ServiceOptions service;
  dds::add_service_options(app, service);
  std::string twin_dir, config_file;
  bool no_twin = false;
  app.add_option("--twin", twin_dir, "Twin store folder (`twinslam twin build` output); required unless --config "
                                     "names twin_dir, and wins over it");
  app.add_option("--config", config_file, "Tiles config YAML: window_m, cache_tiles, twin_dir, max_tiles_on_wire");
  auto* idle = app.add_flag("--no-twin", no_twin, "Serve no twin, only count the inputs (deployment without a store)");
  idle->excludes(app.get_option("--twin"));
  return dds::service_main("tiles", app, service, argc, argv, [&] {
    dds::Node node(service.node);  // first, so a bad QoS file or profile is reported as such whatever else is missing
    dds::Counters counters;
    if (no_twin) {
      // A --config is still read (keys and types), so a bad file fails now and not when a twin arrives.
      if (!config_file.empty()) twinslam::tiles::load_tiles_config(config_file);
      dds::HeartbeatPublisher heartbeat(node, counters);
      twinslam::tiles::wire_idle_inputs(node, counters);
      spdlog::warn("--no-twin: no tiles will be streamed");
      return dds::serve_until_shutdown(heartbeat, node);
    }
    twinslam::tiles::TilesConfig config;
    if (!config_file.empty()) config = twinslam::tiles::load_tiles_config(config_file);
    if (!twin_dir.empty()) config.twin_dir = twin_dir;
    if (config.twin_dir.empty()) {
      throw twinslam::UsageError("--twin TWIN_DIR (or twin_dir in --config, or --no-twin) is required");
    }
    config.validate(config_file.empty() ? "command line" : config_file);
    dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::tiles::TilesNode tiles(node, counters, config);
    return dds::serve_until_shutdown(heartbeat, node);
  });
}
