// `twinslam record OUT.mcap`: every topic of a live pipeline into an MCAP file (mcap_recorder.hpp) until Ctrl-C or
// --duration; `twinslam run --mcap` does the same for a run. Reliable readers (the run's monitor): lossless while
// the pipeline runs lockstep, and each message is counted as it is recorded.
#include <chrono>
#include <cstdio>
#include <thread>

#include "commands.hpp"
#include "mcap_recorder.hpp"
#include "monitor.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/core/shutdown.hpp"

namespace twinslam::cli {

void add_record_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("record", "Record every topic of a live pipeline to an MCAP file");
  auto out = std::make_shared<std::string>();
  auto duration = std::make_shared<double>(0.0);
  auto domain = std::make_shared<int>(-1);
  cmd->add_option("out", *out, "MCAP file to write")->required();
  cmd->add_option("--duration", *duration, "Seconds to record (default: until Ctrl-C)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--domain", *domain, "DDS domain (default: $TWINSLAM_DOMAIN or 0)");
  cmd->callback([=, &exit_code] {
    install_shutdown_handlers();
    McapRecorder recorder(*out);  // throws InputError naming the file if it cannot be written
    {
      dds::NodeConfig config;
      config.service = "record";
      config.vehicle_id = "";
      config.domain = *domain;
      dds::Node node(config);
      MonitorHooks hooks;
      hooks.cdr = [&recorder](const dds::TopicSpec& topic, const std::vector<std::uint8_t>& cdr) {
        recorder.record(topic, cdr);
      };
      hooks.well_known = [&recorder](const std::vector<foxglove::DerivedMessage>& d) { recorder.record(d); };
      TopicMonitor monitor(node, /*reliable=*/true, hooks);
      const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<long>(*duration * 1e3));
      while (!shutdown_requested() && (*duration == 0.0 || std::chrono::steady_clock::now() < end)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }  // readers closed: nothing records any more
    recorder.close();
    std::printf("%s\n%-28s %10s\n", out->c_str(), "TOPIC", "MESSAGES");
    for (const auto& [topic, n] : recorder.counts()) {
      std::printf("%-28s %10llu\n", topic.c_str(), static_cast<unsigned long long>(n));
    }
    exit_code = kExitOk;
  });
}

}  // namespace twinslam::cli
