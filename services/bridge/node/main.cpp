// twinslam-bridge: serves every DDS topic live over the Foxglove WebSocket protocol (open Foxglove, "Open connection",
// ws://HOST:PORT), messages as CDR with the project's IDL as schema and in Foxglove's well-known schemas, and the
// built-in web view on the same port (http://HOST:PORT/, `twinslam view`).
#include <cstdio>

#include <spdlog/spdlog.h>

#include "bridge_node.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  namespace dds = twinslam::dds;
  namespace bridge = twinslam::bridge;
  CLI::App app{"twinslam bridge service: every topic live over the Foxglove WebSocket protocol"};
  dds::ServiceOptions service;
  dds::add_service_options(app, service);
  std::string config_file, address, web_root, origin;
  std::vector<std::string> truth_specs;
  int port = -1;
  app.add_option("--config", config_file, "Bridge config YAML: address, port, max_queued");
  app.add_option("--port", port, "TCP port (default 8765; 0: any free port, printed); wins over --config");
  app.add_option("--address", address, "Interface to listen on (default 0.0.0.0); wins over --config");
  app.add_option("--web-root", web_root, "Directory of the web view (default: the build's); wins over --config");
  app.add_option("--origin", origin, "W's WGS84 origin LAT,LON,H: GNSS fixes also drawn in W; wins over --config");
  app.add_option("--truth", truth_specs, "VEHICLE=FILE: a TUM ground truth (T_WB) drawn as the vehicle flies");
  return dds::service_main("bridge", app, service, argc, argv, [&] {
    dds::Node node(service.node);
    bridge::BridgeConfig config;
    if (!config_file.empty()) config = bridge::load_bridge_config(config_file);
    if (port >= 0) config.port = port;
    if (!address.empty()) config.address = address;
    if (!web_root.empty()) config.web_root = web_root;
    if (!origin.empty()) config.origin = origin;
    config.validate(config_file.empty() ? "command line" : config_file);
    dds::Counters counters;
    dds::HeartbeatPublisher heartbeat(node, counters);
    std::vector<bridge::VehicleTruth> truth;
    for (const std::string& spec : truth_specs) truth.push_back(bridge::load_vehicle_truth(spec));
    bridge::BridgeNode bridge_node(node, counters, config, std::move(truth));
    // One line on stdout with the port: with --port 0 the caller (twinslam run --bridge 0, a test) learns it here.
    std::printf("bridge listening on ws://%s:%u\n", config.address.c_str(), bridge_node.port());
    std::fflush(stdout);
    spdlog::info("Foxglove: open a connection to ws://{}:{}; the web view: http://{}:{}/ (twinslam view)",
                 config.address, bridge_node.port(), config.address, bridge_node.port());
    return dds::serve_until_shutdown(heartbeat, node);
  });
}
