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

// --shared-edge (a fleet on one edge, scripts/fleet.sh): tiles and registration already run in `domain`, started
// outside the run in the edge's partitions; the run starts neither and puts its own processes in the DDS partition
// named after the vehicle. UsageError when it cannot work that way: not a twin mode, no domain given (a private one
// would never meet the edge), a vehicle id that is empty or a pattern, or with --edge-netns / --secure.
void check_shared_edge(const RunOptions& o, bool twin_mode, bool domain_given);

// --external: the services of the pipeline that run outside it (containers, other hosts: docker/demo.sh), started
// with the arguments the run would give them; the run waits for their heartbeats in `domain`, starts the rest and
// records. UsageError for a name that is not tracking, estimator, tiles or registration, for one this run does not use
// (tracking with --features, tiles or registration outside twin modes), without a domain, and with --secure,
// --edge-netns or --shared-edge.
std::set<std::string> external_set(const RunOptions& o, bool twin_mode, bool domain_given);

// Whether the run starts service `s` itself (not the shared edge's tiles or registration, not one of `external`, the
// set external_set returned).
bool started_by_run(const RunOptions& o, const std::set<std::string>& external, const std::string& s);

}  // namespace twinslam::cli
