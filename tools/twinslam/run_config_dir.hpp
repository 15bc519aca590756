#pragma once
// `twinslam run/bench --config-dir DIR`: each service it starts gets `--config DIR/<service>.yaml` when that file
// exists (deploy/config/ holds one commented default per service).
#include <filesystem>
#include <string>
#include <vector>

#include "twinslam/process/supervisor.hpp"

namespace twinslam::cli {

// Before anything starts: InputError "DIR: config directory does not exist" (or "is not a directory"). The files run
// itself can read (ingest.yaml) are loaded here, so their errors come before any service starts. Empty dir: nothing.
void check_config_dir(const std::string& dir);

// {"--config", "DIR/<service>.yaml"} when that file exists, else nothing (the service runs on its defaults).
std::vector<std::string> config_args(const std::string& dir, const std::string& service);

// DIR/<service>.yaml exists and sets the top-level `key` (the run then leaves that setting to the file). Call after
// check_config_dir for files it loads: a file that does not parse counts as not setting it.
bool config_sets_key(const std::string& dir, const std::string& service, const std::string& key);

// A service stopped during start-up. If one exited with code 2 (bad input: its --config, its calibration), throws an
// InputError with that service's own one-line message from its log; otherwise a runtime_error pointing at the logs.
[[noreturn]] void throw_startup_failure(const std::vector<process::ChildResult>& results,
                                        const std::filesystem::path& log_dir);

// One line per service that did not end well: "NAME (ENDED): its last error line" (or "see its log" when it wrote
// none), in the order of `results`; empty when every service exited 0. What `twinslam run` prints when it failed.
std::vector<std::string> failed_service_lines(const std::vector<process::ChildResult>& results,
                                              const std::filesystem::path& log_dir);

}  // namespace twinslam::cli
