// `twinslam launch FILE.yaml`: start the listed services, prefix their output, stop them all on Ctrl-C or when one
// fails; exit 0 only if every service ended cleanly.
#include <iostream>

#include "commands.hpp"
#include "launch_file.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/core/shutdown.hpp"

namespace twinslam::cli {

void add_launch_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("launch", "Start the services of a launch file and supervise them");
  auto file = std::make_shared<std::string>();
  auto grace = std::make_shared<double>(5.0);
  cmd->add_option("file", *file, "Launch file (YAML), e.g. deploy/local.yaml")->required();
  cmd->add_option("--grace", *grace, "Seconds a service gets to stop cleanly before SIGKILL")->capture_default_str();
  cmd->callback([file, grace, &exit_code] {
    const LaunchFile launch = load_launch_file(*file);
    install_shutdown_handlers();
    process::Supervisor supervisor;
    for (const auto& s : launch.services) supervisor.start(s);
    std::cerr << "launch: " << launch.name << ": started " << launch.services.size()
              << " services (Ctrl-C stops them)" << std::endl;
    const auto event = supervisor.watch();
    const auto results = supervisor.stop_all(std::chrono::milliseconds(static_cast<long>(*grace * 1000)));
    for (const auto& e : supervisor.restarts()) {
      std::cerr << "launch: " << e.name << " was restarted at " << e.at_s << " s (restart " << e.attempt << ", pid "
                << e.old_pid << " -> " << e.new_pid << ")" << std::endl;
    }
    bool all_ok = true;
    for (const auto& r : results) {
      if (!r.ok()) {
        all_ok = false;
        std::cerr << "launch: " << r.name << " (pid " << r.pid << ") "
                  << (r.exit_code ? "exited with code " + std::to_string(*r.exit_code)
                                  : "was killed by signal " + std::to_string(r.signal.value_or(0)))
                  << std::endl;
      }
    }
    if (event == process::Supervisor::Event::ChildFailed) all_ok = false;
    exit_code = all_ok ? kExitOk : kExitInternal;
  });
}

}  // namespace twinslam::cli
