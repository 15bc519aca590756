#pragma once
// `twinslam run` as a function, so `twinslam bench` can run every mode in one process.
#include <string>

namespace twinslam::cli {

struct RunOptions {
  std::string dataset, mode = "vio", out, vehicle = "uav0";
  std::string config_dir;  // --config-dir: DIR/<service>.yaml is passed as --config where it exists; empty: none
  std::string weights = "adaptive";  // twin modes: registration information weighting (paper | adaptive | fixed)
  std::string initial_pose;          // twin modes without GNSS: "E N U YAW_DEG" of the body at the first estimate
  bool realtime = false, max = false, features = false, quiet = false;
  bool mcap = false;  // --mcap: every topic recorded to RUN/run.mcap (mcap_recorder.hpp)
  int bridge_port = -1;  // --bridge PORT: twinslam-bridge serves the run live to Foxglove (-1: no bridge)
  int extra_readers = 0;  // --extra-readers N: readers started outside the run (twinslam record, a bridge) ingest awaits
  bool progress = true, no_progress = false;  // a bar (poses / camera frames) with ETA on stderr; --no-progress
  std::string progress_label = "run";         // the bar's label (bench: the mode)
  int domain = -1;
  bool shared_edge = false;  // --shared-edge: tiles and registration of a fleet's edge already run (run_placement.hpp)
  std::string external;  // --external: services started outside the run (containers, another host), comma-separated
  std::string edge_netns;  // --edge-netns NAME: tiles and registration run in that network namespace (ip netns exec)
  bool secure = false;       // --secure: DDS-Security, each process with its role's identity (run_security.hpp)
  std::string security_dir;  // --security-dir: its files (empty: $TWINSLAM_SECURITY_DIR, else the user's state dir)
  double start_timeout_s = 60;
  // --restart: the services that come back after a crash, with back-off (issue 14: the edge services by default;
  // the estimator or tracking only with --realtime, as in lockstep ingest waits for their acknowledgement of each frame)
  std::string restart = "tiles,registration,bridge";
};

// Starts the services, replays the dataset, writes RUN/ (run.json, trajectories, timing, registrations, logs).
// Returns the exit code (0 ok, 1 a service failed); throws InputError/UsageError for bad input.
int run_pipeline(const RunOptions& options);

}  // namespace twinslam::cli
