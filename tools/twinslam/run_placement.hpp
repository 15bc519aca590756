#pragma once
// Where and as whom each process of `twinslam run` runs (issue 14): with --secure its role's DDS-Security profile
// (run_security.hpp), with --edge-netns the edge services in that network namespace (`ip netns exec`, which execs the
// service: same pid, same signals).
#include <filesystem>

#include "run_pipeline.hpp"
#include "twinslam/process/supervisor.hpp"

namespace twinslam::cli {

// `spec` (named after its service) with those options applied; `security_dir` is used only with o.secure.
// UsageError when --edge-netns is set and the service's executable or `ip` is not found.
process::ProcessSpec place_service(process::ProcessSpec spec, const RunOptions& o,
                                   const std::filesystem::path& security_dir);

}  // namespace twinslam::cli
