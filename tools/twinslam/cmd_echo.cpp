// `twinslam echo TOPIC [--count N]`: print the messages of one topic as JSON lines (payload bytes summarized).
#include <atomic>
#include <iostream>
#include <mutex>
#include <thread>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/core/shutdown.hpp"
#include "twinslam/dds/dispatch.hpp"
#include "twinslam/dds/msg_json.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam::cli {

void add_echo_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("echo", "Print the messages of a topic as JSON lines");
  auto topic = std::make_shared<std::string>();
  auto count = std::make_shared<long>(0);
  auto timeout = std::make_shared<double>(0.0);
  auto domain = std::make_shared<int>(-1);
  auto profile = std::make_shared<std::string>("twinslam.local");
  auto security = std::make_shared<std::string>();
  cmd->add_option("topic", *topic, "Topic name, e.g. twinslam/v1/imu or just imu")->required();
  cmd->add_option("--count", *count, "Stop after N messages (0 = until Ctrl-C)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--timeout", *timeout, "Give up after this many seconds (0 = never); exit 1 if fewer than --count");
  cmd->add_option("--domain", *domain, "DDS domain (default: $TWINSLAM_DOMAIN or 0)");
  cmd->add_option("--profile", *profile, "Participant profile (twinslam.secure.ops on a secured domain)")
      ->capture_default_str();
  cmd->add_option("--security", *security, "DDS-Security files of a secured profile (default: $TWINSLAM_SECURITY_DIR)");
  cmd->callback([=, &exit_code] {
    const dds::TopicSpec* spec = dds::find_topic(*topic);
    if (spec == nullptr) {
      std::string known;
      for (const auto& t : dds::topics::kAll) known += (known.empty() ? "" : ", ") + std::string(t.name);
      throw UsageError("unknown topic '" + *topic + "' (known: " + known + ")");
    }
    install_shutdown_handlers();
    dds::NodeConfig config;
    config.service = "echo";
    config.vehicle_id = "";
    config.domain = *domain;
    config.participant_profile = *profile;
    config.security_dir = *security;
    dds::Node node(config);
    auto printed = std::make_shared<std::atomic<long>>(0);
    auto out_mutex = std::make_shared<std::mutex>();
    const long limit = *count;
    dds::with_message_type(*spec, [&]<class T>() {
      node.subscribe<T>(*spec, [=](const T& m) {
        std::lock_guard lock(*out_mutex);
        if (limit > 0 && printed->load() >= limit) return;
        std::cout << nlohmann::json(m).dump() << std::endl;
        if (limit > 0 && printed->fetch_add(1) + 1 >= limit) request_shutdown();
      }, spec->family == dds::QosFamily::Tile ? dds::reader_profile(spec->family) : dds::kMonitorReaderProfile);
    });
    const auto wait = *timeout > 0 ? std::chrono::milliseconds(static_cast<long>(*timeout * 1000))
                                   : std::chrono::hours(24 * 365);
    wait_for_shutdown(wait);
    exit_code = (limit > 0 && printed->load() < limit) ? kExitInternal : kExitOk;
  });
}

}  // namespace twinslam::cli
