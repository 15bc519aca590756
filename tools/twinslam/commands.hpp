#pragma once
// Subcommands of the `twinslam` executable. Each lives in its own cmd_<name>.cpp and registers itself on the app;
// its callback stores the process exit code (CONTRACTS.md: 0 ok, 2 bad usage/input, 1 internal failure) in `exit_code`.
#include <CLI/CLI.hpp>

namespace twinslam::cli {

void add_launch_command(CLI::App& app, int& exit_code);  // cmd_launch.cpp
void add_topics_command(CLI::App& app, int& exit_code);  // cmd_topics.cpp
void add_echo_command(CLI::App& app, int& exit_code);    // cmd_echo.cpp
void add_run_command(CLI::App& app, int& exit_code);     // cmd_run.cpp
void add_eval_command(CLI::App& app, int& exit_code);    // cmd_eval.cpp
void add_sim_command(CLI::App& app, int& exit_code);     // cmd_sim.cpp
void add_bench_command(CLI::App& app, int& exit_code);   // cmd_bench.cpp
void add_twin_command(CLI::App& app, int& exit_code);    // cmd_twin.cpp
void add_twin_changes_command(CLI::App& twin, int& exit_code);  // cmd_twin_changes.cpp: `twin changes`
void add_register_command(CLI::App& app, int& exit_code);  // cmd_register.cpp
void add_gnss_command(CLI::App& app, int& exit_code);      // cmd_gnss.cpp
void add_export_command(CLI::App& app, int& exit_code);    // cmd_export.cpp
void add_record_command(CLI::App& app, int& exit_code);    // cmd_record.cpp
void add_view_command(CLI::App& app, int& exit_code);      // cmd_view.cpp

}  // namespace twinslam::cli
