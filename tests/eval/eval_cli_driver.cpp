// Test-only driver: `eval_cli_driver eval ...` behaves like `twinslam eval ...` (same subcommand code, same exit codes).
#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "twinslam/core/main_guard.hpp"

int main(int argc, char** argv) {
  return twinslam::guarded_main("twinslam", [&] {
    CLI::App app{"twinslam eval test driver"};
    int exit_code = 0;
    twinslam::cli::add_eval_command(app, exit_code);
    app.require_subcommand(1);
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e) == 0 ? twinslam::kExitOk : twinslam::kExitBadInput;
    }
    return exit_code;
  });
}
