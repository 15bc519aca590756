// twinslam: the one command-line entry point (CONTRACTS.md). Subcommands live in cmd_<name>.cpp.
#include "commands.hpp"
#include "twinslam/core/log.hpp"
#include "twinslam/core/main_guard.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam: drift-free visual-inertial SLAM against a city's digital twin"};
  app.require_subcommand(1);
  app.set_version_flag("--version", TWINSLAM_VERSION);
  int exit_code = twinslam::kExitOk;
  twinslam::cli::add_launch_command(app, exit_code);
  twinslam::cli::add_topics_command(app, exit_code);
  twinslam::cli::add_echo_command(app, exit_code);
  twinslam::cli::add_run_command(app, exit_code);
  twinslam::cli::add_eval_command(app, exit_code);
  twinslam::cli::add_sim_command(app, exit_code);
  twinslam::cli::add_bench_command(app, exit_code);
  twinslam::cli::add_twin_command(app, exit_code);
  twinslam::cli::add_register_command(app, exit_code);
  twinslam::cli::add_gnss_command(app, exit_code);
  twinslam::cli::add_export_command(app, exit_code);
  twinslam::cli::add_record_command(app, exit_code);
  twinslam::cli::add_view_command(app, exit_code);
  return twinslam::guarded_main("twinslam", [&] {
    twinslam::init_logging("info");
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e) == 0 ? twinslam::kExitOk : twinslam::kExitBadInput;
    }
    return exit_code;
  });
}
