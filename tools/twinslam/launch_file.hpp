#pragma once
// Launch files (deploy/*.yaml): which service processes to start, with which arguments and environment.
//
//   name: local
//   env: {TWINSLAM_DOMAIN: "${TWINSLAM_DOMAIN:-0}"}     # for every service; ${VAR:-default} is expanded
//   services:
//     - name: tracking
//       exec: twinslam-tracking                         # found next to `twinslam`, then in PATH
//       args: [--realtime]
//       env: {}                                         # per service, overrides the file's env
//       required: false                                 # true: its exit ends the launch
//       cwd: .                                          # relative to the launch file's folder (the default)
//       restart: on-failure                             # or never (the default): restart after a crash, with
//       max_restarts: 5                                 #   back-off 0.5 s doubling to 8 s, at most this often
#include <filesystem>
#include <string>
#include <vector>

#include "twinslam/process/supervisor.hpp"

namespace twinslam::cli {

struct LaunchFile {
  std::string name;
  std::vector<process::ProcessSpec> services;
};

// Throws InputError naming the file and the offending key for unreadable YAML, unknown keys, missing name/exec,
// duplicate service names or an empty service list.
LaunchFile load_launch_file(const std::filesystem::path& file);

}  // namespace twinslam::cli
