#pragma once
// Which services `twinslam run` needs for its mode and the command line each gets (run_placement.hpp then decides
// where and as whom each runs). The same arguments are what an --external service must be started with.
#include <filesystem>
#include <string>
#include <vector>

#include "run_pipeline.hpp"

namespace twinslam::cli {

// What the services' arguments are made of, found once by the run.
struct ServiceInputs {
  std::filesystem::path dataset;     // the dataset's folder
  std::filesystem::path twin_store;  // tiles' store (twin modes; empty when tiles run elsewhere)
  std::string origin;                // W's origin "LAT,LON,ALT" for the estimator (twin and GNSS modes), else empty
  std::string view_origin;           // the same for the bridge's view (also when only the GNSS has one), else empty
  std::filesystem::path truth;       // the dataset's groundtruth.tum for the bridge, empty without one
  std::filesystem::path estimator_checkpoint;  // the estimator's --checkpoint (when it restarts on failure), or empty
};

// The services of the run's pipeline in start order: [tracking,] estimator[, tiles, registration][, bridge].
std::vector<std::string> pipeline_services(const RunOptions& o);

// Service `s`'s arguments (without its --config, run_config_dir.hpp).
std::vector<std::string> service_args(const std::string& s, const RunOptions& o, const ServiceInputs& in);

// Ingest's arguments: the readers of each stream it waits for before its first sample, and in lockstep the stages
// whose acknowledgement each frame waits for. `has_gnss`: the dataset has GNSS fixes.
std::vector<std::string> ingest_args(const RunOptions& o, const ServiceInputs& in, bool has_gnss);

}  // namespace twinslam::cli
