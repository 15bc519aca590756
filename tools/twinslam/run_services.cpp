#include "run_services.hpp"

#include "modes.hpp"
#include "run_config_dir.hpp"

namespace twinslam::cli {

namespace {
std::string replay(const RunOptions& o) { return o.realtime ? "--realtime" : "--max"; }

std::vector<std::string> estimator_args(const RunOptions& o, const ServiceInputs& in) {
  std::vector<std::string> args{"--vehicle", o.vehicle, replay(o), "--camera",
                                (in.dataset / "mav0/cam0/sensor.yaml").string(), "--imu",
                                (in.dataset / "mav0/imu0/sensor.yaml").string()};
  const bool geo = !in.origin.empty();
  if (geo) args.insert(args.end(), {"--origin", in.origin});
  if (fuses_gnss(o.mode)) args.push_back("--fuse-gnss");
  if (fuses_gnss_loose(o.mode)) args.push_back("--fuse-gnss-loose");
  if (uses_twin(o.mode)) {
    args.push_back("--fuse-registrations");
    // Lockstep: each registration is fused at the same frame in every run, whatever the edge's speed.
    if (!o.realtime) args.push_back("--await-registration");
  }
  if (geo && !o.initial_pose.empty()) {
    args.insert(args.end(), {"--initial-pose", o.initial_pose});
  } else if (geo) {
    args.push_back("--align-gnss");
  }
  if (!in.estimator_checkpoint.empty()) args.insert(args.end(), {"--checkpoint", in.estimator_checkpoint.string()});
  return args;
}
}  // namespace

std::vector<std::string> pipeline_services(const RunOptions& o) {
  // With --features the dataset's ideal tracks replace the image frontend.
  std::vector<std::string> services{"estimator"};
  if (!o.features) services.insert(services.begin(), "tracking");
  if (uses_twin(o.mode)) {
    services.push_back("tiles");
    services.push_back("registration");
  }
  if (o.bridge_port >= 0) services.push_back("bridge");
  return services;
}

std::vector<std::string> service_args(const std::string& s, const RunOptions& o, const ServiceInputs& in) {
  if (s == "estimator") return estimator_args(o, in);
  if (s == "bridge") {  // every vehicle; the view also draws the dataset's truth and GNSS in W
    std::vector<std::string> args{"--vehicle", "", replay(o), "--port", std::to_string(o.bridge_port)};
    if (!in.view_origin.empty()) args.insert(args.end(), {"--origin", in.view_origin});
    if (!in.truth.empty()) args.insert(args.end(), {"--truth", o.vehicle + "=" + in.truth.string()});
    return args;
  }
  std::vector<std::string> args{"--vehicle", o.vehicle, replay(o)};
  if (s == "tracking") args.insert(args.end(), {"--camera", (in.dataset / "mav0/cam0/sensor.yaml").string()});
  if (s == "tiles") args.insert(args.end(), {"--twin", in.twin_store.string()});
  if (s == "registration") args.insert(args.end(), {"--weights", o.weights});
  return args;
}

std::vector<std::string> ingest_args(const RunOptions& o, const ServiceInputs& in, bool has_gnss) {
  // Readers ingest must see before its first sample: every subscriber of each stream plus the run's recorder.
  // Camera frames (images, or feature frames with --features) go to tracking or to the estimator.
  // The bridge subscribes to every stream: one more reader of each; so does each --extra-readers recorder (without the
  // wait, a `twinslam record` that discovers ingest late misses the first samples).
  const int viewer = (o.bridge_port >= 0 ? 1 : 0) + o.extra_readers;
  const int imu_readers = (o.features ? 2 : 3) + viewer;
  // GNSS: the recorder, the estimator (global inputs, sensor_worker.hpp), and tiles in twin modes.
  const int gnss_readers = 2 + (uses_twin(o.mode) ? 1 : 0) + viewer;
  std::vector<std::string> args{"--dataset", in.dataset.string(), "--vehicle", o.vehicle, replay(o), "--wait-readers",
                                "imu=" + std::to_string(imu_readers) + ",image=" + std::to_string(2 + viewer) +
                                    ",gnss=" + std::to_string(has_gnss ? gnss_readers : 0)};
  if (o.features) args.push_back("--features");
  // Ingest's wait for its readers (and for READY from those it waits on) gets the run's start-up budget, as the
  // services' own start did: under DDS-Security each new pair of participants must first complete a handshake, which
  // a loaded host can make slow. An ingest.yaml in --config-dir that names start_timeout_s keeps its own.
  if (!config_sets_key(o.config_dir, "ingest", "start_timeout_s")) {
    args.insert(args.end(), {"--start-timeout", std::to_string(o.start_timeout_s)});
  }
  // Lockstep: the next frame goes out once every stage has finished the previous one.
  if (!o.realtime) args.insert(args.end(), {"--ack-from", o.features ? "estimator" : "tracking,estimator"});
  return args;
}

}  // namespace twinslam::cli
