#include "twinslam/dds/service_main.hpp"

#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/log.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/core/shutdown.hpp"

namespace twinslam::dds {

void add_service_options(CLI::App& app, ServiceOptions& options) {
  app.add_option("--vehicle", options.node.vehicle_id, "Vehicle id (the @key of per-vehicle topics)")
      ->capture_default_str();
  app.add_option("--domain", options.node.domain, "DDS domain (default: $TWINSLAM_DOMAIN or 0)");
  app.add_option("--partition", options.node.partition,
                 "DDS partitions, comma-separated, patterns allowed (default: $TWINSLAM_PARTITION, else none)");
  app.add_option("--qos", options.node.qos_file, "Fast DDS XML profile file (default: $TWINSLAM_QOS_FILE or built-in)");
  app.add_option("--profile", options.node.participant_profile, "Participant profile in the QoS file")
      ->capture_default_str();
  app.add_option("--security", options.node.security_dir,
                 "DDS-Security files for a twinslam.secure.* profile (default: $TWINSLAM_SECURITY_DIR)");
  auto* rt = app.add_flag("--realtime", options.realtime, "Live QoS: sensor writers never block");
  app.add_flag("--max", options.lockstep_flag, "Lockstep QoS: lossless, repeatable replay (default)")->excludes(rt);
  app.add_option("--log-level", options.log_level, "trace|debug|info|warn|error")->capture_default_str();
}

int service_main(const std::string& service, CLI::App& app, ServiceOptions& options, int argc, char** argv,
                 const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  return guarded_main("twinslam-" + service, [&] {
    init_logging(options.log_level);
    options.node.service = service;
    options.node.replay = options.realtime ? Replay::Realtime : Replay::Lockstep;
    install_shutdown_handlers();
    return body();
  });
}

}  // namespace twinslam::dds

#include "twinslam/dds/heartbeat.hpp"

namespace twinslam::dds {
int serve_until_shutdown(HeartbeatPublisher& heartbeat, Node& node) {
  heartbeat.set_state(msg::SVC_READY);
  spdlog::info("ready");
  wait_for_shutdown(std::chrono::hours(24 * 365 * 10));
  spdlog::info("stopping");
  node.close_readers();
  return kExitOk;
}
}  // namespace twinslam::dds

namespace twinslam::dds {
int run_wired_service(const std::string& service, const std::string& description, int argc, char** argv,
                      const std::function<void(Node&, Counters&)>& wire) {
  CLI::App app{description};
  ServiceOptions options;
  add_service_options(app, options);
  return service_main(service, app, options, argc, argv, [&] {
    Node node(options.node);
    Counters counters;
    HeartbeatPublisher heartbeat(node, counters);
    wire(node, counters);
    return serve_until_shutdown(heartbeat, node);
  });
}
}  // namespace twinslam::dds
