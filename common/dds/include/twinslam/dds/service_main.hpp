#pragma once
// What every service executable shares: the common command-line options (vehicle, domain, QoS file and profile,
// replay mode, log level), logging set-up, signal handling and the exit-code mapping of CONTRACTS.md.
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "twinslam/dds/node.hpp"

namespace twinslam::dds {

struct ServiceOptions {
  NodeConfig node;
  bool realtime = false;           // --realtime: live QoS (never block); default --max: lockstep QoS
  bool lockstep_flag = false;      // --max (the default; present for symmetry with `twinslam run`)
  std::string log_level = "info";
};

// Adds --vehicle --domain --partition --qos --profile --realtime/--max --log-level to `app`.
void add_service_options(CLI::App& app, ServiceOptions& options);

// Parses argv, sets up logging and SIGINT/SIGTERM handling, then runs body(options) inside guarded_main.
// Exit codes: 0 ok, 2 bad usage or input, 1 internal failure.
int service_main(const std::string& service, CLI::App& app, ServiceOptions& options, int argc, char** argv,
                 const std::function<int()>& body);

}  // namespace twinslam::dds

namespace twinslam::dds {
class HeartbeatPublisher;
// Marks the service READY and blocks until SIGINT/SIGTERM; the usual tail of a service's main. Then closes the
// node's readers, so no DDS callback can reach the service objects the caller destroys next.
int serve_until_shutdown(HeartbeatPublisher& heartbeat, Node& node);
}  // namespace twinslam::dds

namespace twinslam::dds {
class Counters;
// The whole main of a service that only wires topics: common options, a Node, a heartbeat with `counters`, then
// `wire(node, counters)` and serve until SIGINT/SIGTERM.
int run_wired_service(const std::string& service, const std::string& description, int argc, char** argv,
                      const std::function<void(Node&, Counters&)>& wire);
}  // namespace twinslam::dds
