#pragma once
// The ingest service's one config struct (deploy/config/ingest.yaml): replay pacing and how long lockstep replay
// waits for its consumers. The command line's --speed, --start-timeout and --ack-timeout win over the file.
//   speed: 1.0             # realtime pacing factor
//   start_timeout_s: 30    # wait for every consumer before the first sample [s]
//   ack_timeout_s: 30      # wait for a frame's acknowledgement under --max [s]
//   faults: {...}          # sensor faults injected into the replay (faults.hpp); none by default
#include <string>

#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/ingest/faults.hpp"

namespace twinslam::ingest {

struct IngestConfig {
  double speed = 1.0;            // --realtime pacing factor (2 = twice as fast as recorded)
  // Services start in parallel and a cold start (DDS discovery, loading a twin) takes seconds; 30 s leaves room on a
  // loaded 2-core machine without hanging a broken pipeline for long [s].
  double start_timeout_s = 30.0;
  // Lockstep: the longest a frame may take through every acknowledging service before ingest gives up [s].
  double ack_timeout_s = 30.0;
  FaultConfig faults;  // injected sensor faults (tests and demonstrations of fault handling)

  // Throws twinslam::InputError "SOURCE: ingest key 'K': what" naming the first bad field.
  void validate(const std::string& source = "IngestConfig") const;
};

// Binds every key of the YAML form to `config` (one line per field).
void bind_ingest_config(yaml::Fields& fields, IngestConfig& config);

// Parses YAML text over `base` and validates; unknown keys, wrong types and out-of-range values throw InputError
// naming the file, the line where there is one, and the key.
IngestConfig parse_ingest_config(const std::string& text, const std::string& file, const IngestConfig& base = {});
IngestConfig load_ingest_config(const std::string& path, const IngestConfig& base = {});

}  // namespace twinslam::ingest
