#pragma once
// Where and as whom each process of `twinslam run` runs (issue 14): with --secure its role's DDS-Security profile
// (run_security.hpp), with --edge-netns the edge services in that network namespace (`ip netns exec`, which execs the
// service: same pid, same signals); with --restart which of them come back after a crash.
#include <filesystem>
#include <set>
#include <string>

#include "run_pipeline.hpp"
#include "twinslam/process/supervisor.hpp"

namespace twinslam::cli {

// `spec` (named after its service) with those options applied; `security_dir` is used only with o.secure.
// UsageError when --edge-netns is set and the service's executable or `ip` is not found.
process::ProcessSpec place_service(process::ProcessSpec spec, const RunOptions& o,
                                   const std::filesystem::path& security_dir);

// The services named by --restart (comma-separated, "none" for none). UsageError naming an unknown service, and for
// estimator or tracking without --realtime (lockstep ingest would wait for a dead stage's acknowledgement).
std::set<std::string> restart_set(const RunOptions& o);

}  // namespace twinslam::cli
