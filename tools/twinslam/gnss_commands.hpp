#pragma once
// The subcommands under `twinslam gnss` (cmd_gnss.cpp adds the group and `solve`).
#include <CLI/CLI.hpp>

namespace twinslam::cli {

void add_gnss_errors_command(CLI::App& gnss, int& exit_code);  // cmd_gnss_errors.cpp

}  // namespace twinslam::cli
