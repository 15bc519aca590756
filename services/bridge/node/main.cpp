// twinslam-bridge: serves every DDS topic live over the Foxglove WebSocket protocol (open Foxglove, "Open connection",
// ws://HOST:PORT), messages as CDR with the project's IDL as schema.
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
  std::string config_file, address;
  int port = -1;
  app.add_option("--config", config_file, "Bridge config YAML: address, port, max_queued");
  app.add_option("--port", port, "TCP port (default 8765; 0: any free port, printed); wins over --config");
  app.add_option("--address", address, "Interface to listen on (default 0.0.0.0); wins over --config");
  return dds::service_main("bridge", app, service, argc, argv, [&] {
    dds::Node node(service.node);
    bridge::BridgeConfig config;
    if (!config_file.empty()) config = bridge::load_bridge_config(config_file);
    if (port >= 0) config.port = port;
    if (!address.empty()) config.address = address;
    config.validate(config_file.empty() ? "command line" : config_file);
    dds::Counters counters;
    dds::HeartbeatPublisher heartbeat(node, counters);
    bridge::BridgeNode bridge_node(node, counters, config);
    // One line on stdout with the port: with --port 0 the caller (twinslam run --bridge 0, a test) learns it here.
    std::printf("bridge listening on ws://%s:%u\n", config.address.c_str(), bridge_node.port());
    std::fflush(stdout);
    spdlog::info("Foxglove: open a connection to ws://{}:{}", config.address, bridge_node.port());
    return dds::serve_until_shutdown(heartbeat, node);
  });
}
