// `twinslam topics`: the live services (from their heartbeats) and topics (type, writers, message rate).
#include <cstdio>
#include <iostream>
#include <thread>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "monitor.hpp"
#include "twinslam/core/main_guard.hpp"

namespace twinslam::cli {

void add_topics_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("topics", "List live services and topics with their types and message rates");
  auto window = std::make_shared<double>(2.0);
  auto json = std::make_shared<bool>(false);
  auto domain = std::make_shared<int>(-1);
  cmd->add_option("--window", *window, "Seconds to listen")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--domain", *domain, "DDS domain (default: $TWINSLAM_DOMAIN or 0)");
  cmd->add_flag("--json", *json, "One JSON object on stdout");
  cmd->callback([=, &exit_code] {
    dds::NodeConfig config;
    config.service = "topics";
    config.vehicle_id = "";
    config.domain = *domain;
    dds::Node node(config);
    TopicMonitor monitor(node, /*reliable=*/false);
    std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<long>(*window * 1000)));
    const auto topics = monitor.stats();
    const auto services = monitor.services();
    if (*json) {
      nlohmann::json j{{"window_s", *window}, {"services", nlohmann::json::array()}, {"topics", nlohmann::json::array()}};
      for (const auto& s : services) {
        j["services"].push_back({{"service", s.service}, {"instance", s.instance}, {"vehicle_id", s.vehicle_id},
                                 {"state", s.state}, {"uptime_ms", s.uptime_ms}, {"counters", s.counters}});
      }
      for (const auto& t : topics) {
        if (t.writers == 0 && t.messages == 0) continue;
        j["topics"].push_back({{"name", t.name}, {"type", t.type}, {"writers", t.writers},
                               {"messages", t.messages}, {"rate_hz", t.messages / *window}});
      }
      std::cout << j.dump() << std::endl;
    } else {
      std::printf("%-14s %-22s %-8s %-9s %s\n", "SERVICE", "INSTANCE", "VEHICLE", "STATE", "UPTIME_S");
      for (const auto& s : services) {
        std::printf("%-14s %-22s %-8s %-9s %.1f\n", s.service.c_str(), s.instance.c_str(), s.vehicle_id.c_str(),
                    s.state.c_str(), s.uptime_ms / 1000.0);
      }
      std::printf("\n%-28s %-30s %7s %9s\n", "TOPIC", "TYPE", "WRITERS", "RATE_HZ");
      for (const auto& t : topics) {
        if (t.writers == 0 && t.messages == 0) continue;
        std::printf("%-28s %-30s %7d %9.1f\n", t.name.c_str(), t.type.c_str(), t.writers, t.messages / *window);
      }
    }
    exit_code = kExitOk;
  });
}

}  // namespace twinslam::cli
