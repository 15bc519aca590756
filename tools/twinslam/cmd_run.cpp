// `twinslam run DIR --mode MODE --out RUN`: runs the service pipeline on one dataset and records what it produced.
// The services are separate processes on a private DDS domain (so runs and tests never hear each other); this
// process records every topic reliably, waits for ingest to finish the dataset, stops the services, and writes RUN/.
#include <atomic>
#include <chrono>
#include <optional>
#include <set>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <thread>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include <Eigen/Eigenvalues>

#include "modes.hpp"
#include "mcap_recorder.hpp"
#include "monitor.hpp"
#include "dataset_twin.hpp"
#include "run_config_dir.hpp"
#include "run_pipeline.hpp"
#include "twinslam/dds/convert.hpp"
#include "run_hooks.hpp"
#include "run_record.hpp"
#include "run_services.hpp"
#include "run_placement.hpp"
#include "run_security.hpp"
#include "twin_changes_report.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/core/progress.hpp"
#include "twinslam/core/shutdown.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/features.hpp"
#include "twinslam/process/domain_claim.hpp"
#include "twinslam/process/supervisor.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

namespace {
// A twin-mode run's twin-change report (twinslam twin changes); a run that cannot be compared keeps its outputs and
// says why on stderr.
void write_changes_of_run(const fs::path& out, bool quiet) {
  try {
    write_twin_change_report(out, out, {}, /*print=*/!quiet);  // bench runs quietly: its table stays alone
  } catch (const InputError& e) {
    std::cerr << "twinslam run: no twin-change report: " << e.what() << std::endl;
  }
}

// The domain the user gave (--domain, else TWINSLAM_DOMAIN), if any.
std::optional<int> given_domain(int requested) {
  if (requested >= 0) return requested;
  if (const char* env = std::getenv("TWINSLAM_DOMAIN"); env != nullptr && *env != '\0') return std::atoi(env);
  return std::nullopt;
}

// Else a private one per run, claimed on this host (domain_claim.hpp): parallel runs and tests stay apart.
int pick_domain(std::optional<int> given) {
  return given ? *given : process::claim_dds_domain(100, 100, static_cast<unsigned>(getpid()));
}

}  // namespace

int run_pipeline(const RunOptions& o) {
  // Refused before anything starts or is written: run.json must never name a mode that did not run.
  require_implemented_mode(o.mode);
  const std::set<std::string> restartable = restart_set(o);
  const std::optional<int> domain_given = given_domain(o.domain);
  check_shared_edge(o, uses_twin(o.mode), domain_given.has_value());
  const std::set<std::string> external = external_set(o, uses_twin(o.mode), domain_given.has_value());
  // Bad input ends here, before anything starts.
  const auto dataset =
      ingest::load_dataset(o.dataset, o.features ? ingest::CameraInput::kFeatureTracks : ingest::CameraInput::kImages);
  // The camera frames the estimator will see: the images, or the feature tracks' frames (there may be no image).
  const std::size_t camera_frames =
      o.features ? ingest::load_feature_tracks(dataset.root / "mav0/cam0/features.csv").size() : dataset.images.size();
  check_config_dir(o.config_dir);
  // Twin modes: W's origin and the twin store (built once per twin content), and how T_WL is first found.
  std::optional<DatasetGeo> geo;
  fs::path twin_store;
  if (needs_gnss(o.mode) && dataset.gnss.empty()) {
    throw UsageError("mode '" + o.mode + "': the dataset has no GNSS (mav0/gnss0)");
  }
  if (fuses_gnss_loose(o.mode) && !o.initial_pose.empty()) {
    throw UsageError("mode '" + o.mode + "': its pose graph starts from the GNSS alignment; --initial-pose is not used");
  }
  if (uses_twin(o.mode) || needs_gnss(o.mode)) geo = read_dataset_geo(dataset.root);
  // The bridge and the MCAP recording draw GNSS in W in every mode (the estimator gets an origin only in the modes above).
  std::optional<DatasetGeo> view_geo = geo;
  if (!view_geo && (o.bridge_port >= 0 || o.mcap) && !dataset.gnss.empty()) {
    try {  // a dataset without an origin still runs: its fixes are then only on Foxglove's Map panel
      view_geo = read_dataset_geo(dataset.root);
    } catch (const InputError&) {
    }
  }
  if (uses_twin(o.mode)) {
    if (dataset.gnss.empty() && o.initial_pose.empty()) {
      throw UsageError("mode '" + o.mode + "': the dataset has no GNSS (mav0/gnss0) for the initial alignment; give "
                       "--initial-pose \"E N U YAW_DEG\"");
    }
    // Else the edge's tiles serve their own store.
    if (started_by_run(o, external, "tiles")) twin_store = dataset_twin_store(*geo, o.quiet);
  }
  const fs::path out = o.out;
  fs::create_directories(out);
  const int domain = pick_domain(domain_given);
  install_shutdown_handlers();
  const auto wall0 = std::chrono::steady_clock::now();

  const fs::path security = o.secure ? ensure_security_files(o.security_dir, o.quiet) : fs::path();
  dds::NodeConfig cfg;
  cfg.service = "run";
  cfg.vehicle_id = o.vehicle;
  cfg.domain = domain;
  if (o.shared_edge) cfg.partition = o.vehicle;  // this vehicle's topics and the edge's, no other vehicle's
  if (o.secure) {
    cfg.participant_profile = secure_profile("run");
    cfg.security_dir = security.string();
  }
  dds::Node recorder(cfg);
  RunRecord record;
  const auto since_ms = [wall0] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
  };
  std::atomic<std::size_t> poses{0};  // frames the estimator has finished: the progress of the run
  MonitorHooks hooks = record_hooks(record, o.vehicle, o.features, since_ms, poses);
  // Declared before the monitor: its readers (which record into it) close first.
  std::unique_ptr<McapRecorder> mcap;
  if (o.mcap) {
    mcap = std::make_unique<McapRecorder>((out / "run.mcap").string());
    hooks.cdr = [&mcap](const dds::TopicSpec& topic, const std::vector<std::uint8_t>& cdr) {
      mcap->record(topic, cdr);
    };
    hooks.well_known = [&mcap](const std::vector<foxglove::DerivedMessage>& d) { mcap->record(d); };
  }
  TopicMonitor monitor(recorder, /*reliable=*/true, hooks);
  const fs::path truth = dataset.root / "groundtruth.tum";
  if (o.mcap) {  // the recording's well-known channels hold the truth and GNSS in W too, as the bridge's do
    if (fs::is_regular_file(truth)) monitor.well_known().set_truth(o.vehicle, foxglove::read_truth_tum(truth.string()));
    if (view_geo) monitor.well_known().set_origin(origin_text(view_geo->origin));
  }

  // An estimator restarted on failure resumes from its checkpoint in the run's folder (resume.hpp); one left by an
  // earlier run there is not this flight's.
  if (restartable.contains("estimator")) fs::remove(out / "estimator.checkpoint.json");
  const ServiceInputs inputs{dataset.root, twin_store, geo ? origin_text(geo->origin) : "",
                             view_geo ? origin_text(view_geo->origin) : "",
                             fs::is_regular_file(truth) ? truth : fs::path(),
                             restartable.contains("estimator") ? out / "estimator.checkpoint.json" : fs::path()};
  const std::vector<std::string> services = pipeline_services(o);
  process::Supervisor supervisor({out / "logs"});
  std::map<std::string, std::string> env{{"TWINSLAM_DOMAIN", std::to_string(domain)}};
  if (o.shared_edge) env["TWINSLAM_PARTITION"] = o.vehicle;
  for (const auto& s : services) {
    std::vector<std::string> args = service_args(s, o, inputs);
    if (!started_by_run(o, external, s)) {  // the shared edge's or --external: awaited below like the run's own
      if (external.contains(s) && !o.quiet) {
        std::string line = "twinslam-" + s;
        for (const auto& a : args) {
          // The run builds no store for external tiles: they serve their own (`twinslam twin build`).
          const std::string shown = s == "tiles" && a.empty() ? "STORE" : a;
          line += " " + (shown.empty() || shown.find(' ') != std::string::npos ? "'" + shown + "'" : shown);
        }
        std::cerr << "twinslam run: waiting for the external " << s << " (as the run would start it: " << line << ")"
                  << std::endl;
      }
      continue;
    }
    for (auto& a : config_args(o.config_dir, s)) args.push_back(std::move(a));
    process::ProcessSpec spec = place_service({s, "twinslam-" + s, args, env, {}, false}, o, security);
    // --restart: the services that come back after a crash (by default the edge's: the estimator flies on without
    // them meanwhile, issue 14).
    spec.restart_on_failure = restartable.contains(s);
    supervisor.start(spec);
  }
  const auto ready_deadline = std::chrono::steady_clock::now() +
                              std::chrono::milliseconds(static_cast<long>(o.start_timeout_s * 1000));
  while (!monitor.all_ready(services)) {
    if (supervisor.watch(std::chrono::milliseconds(20)) != process::Supervisor::Event::Timeout) {
      throw_startup_failure(supervisor.stop_all(), out / "logs");  // exit 2 with its line if its input was bad
    }
    if (std::chrono::steady_clock::now() > ready_deadline) {
      throw std::runtime_error(
          o.shared_edge ? "services not ready in time (is the shared edge's tiles and registration running in domain " +
                              std::to_string(domain) + ", partitions 'edge,*'?)"
          : !external.empty() ? "services not ready in time (are the --external ones running in domain " +
                                    std::to_string(domain) + "?)"
                              : "services not ready in time");
    }
  }
  std::vector<std::string> ingest = ingest_args(o, inputs, !dataset.gnss.empty());
  for (auto& a : config_args(o.config_dir, "ingest")) ingest.push_back(std::move(a));
  supervisor.start(place_service({"ingest", "twinslam-ingest", ingest, env, {}, true}, o, security));
  // One pose per camera frame: the bar counts the estimator's poses against the dataset's frames.
  Progress progress(o.progress_label, camera_frames, o.progress);
  auto event = process::Supervisor::Event::Timeout;
  while ((event = supervisor.watch(std::chrono::milliseconds(250))) == process::Supervisor::Event::Timeout) {
    progress.update(poses.load(std::memory_order_relaxed));
  }
  progress.finish(poses.load(std::memory_order_relaxed));
  const auto results = supervisor.stop_all();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  bool ok = event == process::Supervisor::Event::RequiredExited;
  nlohmann::json svc = nlohmann::json::object();
  for (const auto& r : results) {
    ok = ok && r.ok();
    svc[r.name] = r.exit_code ? nlohmann::json(*r.exit_code) : nlohmann::json("signal " + std::to_string(*r.signal));
  }
  nlohmann::json messages = nlohmann::json::object();
  unsigned long long frames = 0;
  for (const auto& t : monitor.stats()) {
    if (t.name != dds::topics::kHeartbeat.name) messages[t.name] = t.messages;
    // Frames finished by the pipeline: those the estimator turned into a pose.
    if (t.name == dds::topics::kOdometry.name) frames = t.messages;
  }
  const std::string status = event == process::Supervisor::Event::Shutdown ? "interrupted" : ok ? "ok" : "failed";
  nlohmann::json run{{"mode", o.mode},
                     {"dataset", dataset.root.string()},
                     {"version", TWINSLAM_VERSION},
                     {"wall_time_s", wall_s},
                     {"frames_processed", frames},
                     {"status", status},
                     {"replay", o.realtime ? "realtime" : "max"},
                     {"config_dir", o.config_dir.empty() ? nlohmann::json()  // null: every service on its defaults
                                                         : nlohmann::json(fs::absolute(o.config_dir).string())},
                     {"domain", domain},
                     {"secure", o.secure},
                     {"edge_netns", o.edge_netns.empty() ? nlohmann::json() : nlohmann::json(o.edge_netns)},
                     {"shared_edge", o.shared_edge},
                     {"external", external},
                     {"messages", messages},
                     {"services", svc},
                     {"poses", record.odometry_count()}};
  nlohmann::json restarts = nlohmann::json::array();
  for (const auto& e : supervisor.restarts()) {
    restarts.push_back({{"service", e.name}, {"at_s", e.at_s}, {"attempt", e.attempt},
                        {"ended", process::describe_end(e.exit_code, e.signal)},
                        {"old_pid", e.old_pid}, {"new_pid", e.new_pid}});
  }
  run["restarts"] = restarts;
  // Each service's counters from the last heartbeat of each of its processes that reached this recorder (summed over
  // a restarted service's processes): what it rejected, dropped or met on the way (faults.hpp, issue 15).
  nlohmann::json counters = nlohmann::json::object();
  for (const ServiceInfo& s : monitor.services()) {
    nlohmann::json& c = counters[s.service];
    if (c.is_null()) c = nlohmann::json::object();
    for (const auto& [name, value] : s.counters) c[name] = c.value(name, 0ULL) + value;
  }
  run["counters"] = counters;
  // Poses that carried each Odometry fault bit (exact: Odometry is reliable, unlike the best-effort heartbeats).
  run["odometry_faults"] = record.odometry_faults();
  // When T_WB entered W (null: never): world-frame evaluations start there (twinslam bench).
  const auto aligned = record.first_aligned_stamp_ns(), first = record.first_estimate_stamp_ns();
  run["aligned_from_stamp_ns"] = aligned ? nlohmann::json(*aligned) : nlohmann::json();
  run["out_of_world_ns"] = record.out_of_world_after_alignment();
  run["aligned_after_s"] = aligned && first ? nlohmann::json(1e-9 * static_cast<double>(*aligned - *first))
                                            : nlohmann::json();
  if (const auto [median, largest] = record.local_map_landmarks(); largest > 0) {
    run["local_map_landmarks"] = {{"median", median}, {"max", largest}};
  }
  if (const auto latency = record.pipeline_latency(); latency.count > 0) {
    // LocalMap -> Registration, both seen by this process (services/registration/README.md).
    run["registration_latency_ms"] = {{"count", latency.count}, {"median", latency.median_ms}, {"p99", latency.p99_ms}};
  }
  if (geo) {
    // W's origin, so exports (twinslam export) place the run on Earth without the dataset at hand.
    run["origin"] = {{"lat_deg", geo->origin.lat_deg}, {"lon_deg", geo->origin.lon_deg}, {"alt_m", geo->origin.alt_m}};
  }
  if (uses_twin(o.mode)) {
    run["twin"] = {{"store", twin_store.empty() ? nlohmann::json() : nlohmann::json(twin_store.string())},
                   {"weights", o.weights},
                   {"initial_alignment", o.initial_pose.empty() ? std::string("gnss") : "pose " + o.initial_pose}};
  }
  if (mcap) {
    mcap->close();  // every service has stopped: nothing of the run is still on its way
    nlohmann::json counts = nlohmann::json::object();
    for (const auto& [topic, n] : mcap->counts()) counts[topic] = n;
    run["mcap"] = {{"file", "run.mcap"}, {"messages", counts}};
  }
  record.write(out);
  std::ofstream(out / "run.json") << run.dump(2) << '\n';
  if (uses_twin(o.mode) && fs::exists(out / "landmarks.csv")) write_changes_of_run(out, o.quiet);

  if (status == "failed") {  // also when quiet: which service failed, and why, in its own words
    std::cerr << "twinslam run: a service failed; logs in " << (out / "logs").string() << std::endl;
    for (const auto& line : failed_service_lines(results, out / "logs")) std::cerr << "  " << line << std::endl;
  }
  if (o.quiet) return status == "failed" ? kExitInternal : kExitOk;
  std::printf("run %s: %s in %.1f s (mode %s, %s replay, domain %d)\n", out.string().c_str(), status.c_str(), wall_s,
              o.mode.c_str(), o.realtime ? "realtime" : "lockstep", domain);
  std::printf("%-28s %10s\n", "TOPIC", "MESSAGES");
  for (const auto& [name, count] : messages.items()) std::printf("%-28s %10llu\n", name.c_str(), count.get<unsigned long long>());
  std::printf("dataset: %zu IMU, %zu images, %zu GNSS", dataset.imu.size(), dataset.images.size(), dataset.gnss.size());
  if (o.features) std::printf(", %zu feature frames (replayed)", camera_frames);
  std::printf("\n");
  return status == "failed" ? kExitInternal : kExitOk;
}

void add_run_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("run", "Run the service pipeline on a dataset and write RUN/");
  auto o = std::make_shared<RunOptions>();
  cmd->add_option("dataset", o->dataset, "Dataset folder (EuRoC ASL layout)")->required();
  cmd->add_option("--mode", o->mode, "vio | vio-gnss | vio-gnss-loose | vio-twin | vio-twin-gnss (implemented: " +
                                         implemented_modes_text() + ")")
      ->check(CLI::IsMember(all_modes()))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder RUN")->required();
  auto* rt = cmd->add_flag("--realtime", o->realtime, "Pace sensors by the wall clock");
  cmd->add_flag("--max", o->max, "Lockstep replay, as fast as the services allow (default)")->excludes(rt);
  cmd->add_flag("--features", o->features, "Feed the dataset's ideal feature tracks instead of images");
  cmd->add_option("--vehicle", o->vehicle, "Vehicle id")->capture_default_str();
  cmd->add_option("--domain", o->domain, "DDS domain (default: $TWINSLAM_DOMAIN, else a private one)");
  cmd->add_flag("--secure", o->secure,
                "DDS-Security: every process authenticated (drone, edge, ops identities), topics access-controlled, "
                "payloads encrypted; files made on first use");
  cmd->add_option("--security-dir", o->security_dir,
                  "With --secure: the CA, identities and permissions (default: $TWINSLAM_SECURITY_DIR, else "
                  "~/.local/state/twinslam/pki)");
  cmd->add_flag("--shared-edge", o->shared_edge,
                "Twin modes: tiles and registration of a fleet's edge already run in --domain (scripts/fleet.sh); "
                "start neither, talk in the DDS partition named after --vehicle");
  cmd->add_option("--external", o->external,
                  "Services started outside the run (containers, other hosts: docker/demo.sh), comma-separated from "
                  "tracking, estimator, tiles, registration; the run waits for them in --domain");
  cmd->add_option("--edge-netns", o->edge_netns,
                  "Run tiles and registration in this network namespace (`ip netns exec`; scripts/two-hosts.sh)");
  cmd->add_option("--restart", o->restart,
                  "Services restarted after a crash, with back-off, comma-separated (estimator and tracking need "
                  "--realtime; none: never)")
      ->capture_default_str();
  cmd->add_option("--start-timeout", o->start_timeout_s, "Seconds for the services to get ready")->capture_default_str();
  cmd->add_option("--weights", o->weights, "Twin modes: registration information weighting")
      ->check(CLI::IsMember({"paper", "adaptive", "fixed"}))
      ->capture_default_str();
  cmd->add_option("--initial-pose", o->initial_pose,
                  "Twin modes without GNSS: \"E N U YAW_DEG\", the body's pose in W at the first estimate");
  cmd->add_option("--config-dir", o->config_dir, "Folder of <service>.yaml configs (e.g. deploy/config)");
  cmd->add_flag("--no-progress", o->no_progress, "No progress bar on stderr");
  cmd->add_flag("--mcap", o->mcap, "Record every topic to RUN/run.mcap (CDR messages, OMG IDL schemas)");
  cmd->add_option("--bridge", o->bridge_port, "Serve the run live to Foxglove on this port (twinslam-bridge)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--extra-readers", o->extra_readers,
                  "Readers of every stream started outside the run (twinslam record, twinslam-bridge) to wait for")
      ->check(CLI::Range(0, 16));
  cmd->callback([o, &exit_code] {
    o->progress = !o->no_progress;
    exit_code = run_pipeline(*o);
  });
}

}  // namespace twinslam::cli
