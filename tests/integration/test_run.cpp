// `twinslam run` on the EuRoC excerpt: all services start as processes, the whole dataset flows in lockstep, and
// run.json records exactly what flowed.
#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "wait_for.hpp"

namespace fs = std::filesystem;
using namespace twinslam;
using namespace std::chrono_literals;

TEST(Run, EurocExcerptFlowsThroughTheServices) {
  const fs::path out = fs::temp_directory_path() / ("twinslam_run_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = test::run_process({test::bin("twinslam"), "run",
                                    std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro", "--mode", "vio",
                                    "--out", out.string(), "--domain", std::to_string(test::test_domain())},
                                   {}, std::chrono::seconds(150));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // Progress on stderr (plain lines: not a terminal): the estimator's poses against the dataset's 95 frames.
  EXPECT_NE(r.err.find("run        [##############################] 100% 95/95"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ETA"), std::string::npos) << r.err;
  std::ifstream in(out / "run.json");
  const auto run = nlohmann::json::parse(in);
  EXPECT_EQ(run["status"], "ok");
  EXPECT_EQ(run["mode"], "vio");
  EXPECT_EQ(run["messages"]["twinslam/v1/imu"], 29120);
  EXPECT_EQ(run["messages"]["twinslam/v1/image"], 95);
  EXPECT_EQ(run["frames_processed"], 95);  // every frame acknowledged by tracking
  // The tracking service turned every image into a feature frame (EuRoC: >= 100 features after the first frames).
  EXPECT_EQ(run["messages"]["twinslam/v1/features"], 95);
  for (const auto& [name, code] : run["services"].items()) EXPECT_EQ(code, 0) << name;
  EXPECT_TRUE(fs::exists(out / "logs/ingest.log"));
  fs::remove_all(out);
}

// --config-dir reaches the services: an estimator told to wait 100 s for rest and not to initialize in motion never
// initializes on the 5 s excerpt, so the run (still ok) writes no trajectory; run.json names the directory.
TEST(Run, ConfigDirReachesTheServicesAndIsRecorded) {
  const fs::path out = fs::temp_directory_path() / ("twinslam_run_cfg_" + std::to_string(::getpid()));
  const fs::path cfg = out.string() + "_config";
  fs::remove_all(out);
  fs::remove_all(cfg);
  fs::create_directories(cfg);
  std::ofstream(cfg / "estimator.yaml") << "static_window_s: 100\nmotion_init:\n  enabled: false\n";
  const auto r = test::run_process({test::bin("twinslam"), "run",
                                    std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro", "--mode", "vio",
                                    "--out", out.string(), "--domain", std::to_string(test::test_domain()),
                                    "--config-dir", cfg.string()},
                                   {}, std::chrono::seconds(150));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::ifstream in(out / "run.json");
  const auto run = nlohmann::json::parse(in);
  EXPECT_EQ(run["status"], "ok");
  EXPECT_EQ(run["config_dir"], fs::absolute(cfg).string());
  EXPECT_EQ(run["frames_processed"], 95);     // every frame still got an (uninitialized) odometry message
  EXPECT_FALSE(fs::exists(out / "trajectory_local.tum"));  // but none was an estimate
  fs::remove_all(out);
  fs::remove_all(cfg);
}

namespace {

// The pid of `parent`'s child whose command name starts with `comm` (/proc/PID/stat), or -1.
pid_t child_named(pid_t parent, const std::string& comm) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    const auto open = line.find('('), close = line.rfind(')');
    if (open == std::string::npos || close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid == parent && line.compare(open + 1, comm.size(), comm) == 0) return std::stoi(line.substr(0, open));
  }
  return -1;
}

// A fresh base folder for a test and `twinslam sim --scenario tiny --features` in base/tiny.
test::ProcessOutput simulate_tiny(const fs::path& base) {
  fs::remove_all(base);
  return test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out", (base / "tiny").string(),
                            "--features", "--quiet"}, {}, std::chrono::seconds(120));
}

}  // namespace

// Issue 14: the edge services restart after a crash. Registration is killed with SIGKILL mid-flight; the run goes on,
// brings it back, ends ok and lists the restart in run.json; the new process answers LocalMaps again.
TEST(Run, AKilledRegistrationServiceIsRestartedAndTheRunEndsOk) {
  const fs::path base = fs::temp_directory_path() / ("twinslam_run_restart_" + std::to_string(::getpid()));
  const auto sim = simulate_tiny(base);
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  test::Background run({test::bin("twinslam"), "run", (base / "tiny").string(), "--mode", "vio-twin", "--features",
                        "--out", (base / "run").string(), "--domain", std::to_string(test::test_domain())});
  pid_t registration = -1;
  ASSERT_TRUE(twinslam::testing::wait_for([&] { return (registration = child_named(run.pid(), "twinslam-regist")) > 0; }, 60s))
      << run.output();
  // Mid-flight, as the fault is: ingest has loaded the dataset and replays (tiny takes ~25 s under --max),
  // so registrations have been flowing for a few seconds. (A kill during the services' start-up, before the replay,
  // has been seen to hang the run in 2 of 9 tries — not yet understood, see the README's limits.)
  const auto ingest_log = [&] {
    std::ifstream in(base / "run/logs/ingest.log");
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  ASSERT_TRUE(twinslam::testing::wait_for([&] { return ingest_log().find("feature tracks") != std::string::npos; },
                                          60s));
  std::this_thread::sleep_for(6s);
  ASSERT_EQ(::kill(registration, SIGKILL), 0);
  ASSERT_EQ(run.wait(std::chrono::milliseconds(180'000)), 0) << run.output();
  std::ifstream in(base / "run/run.json");
  const auto json = nlohmann::json::parse(in);
  EXPECT_EQ(json["status"], "ok");
  ASSERT_EQ(json["restarts"].size(), 1u) << json.dump();
  EXPECT_EQ(json["restarts"][0]["service"], "registration");
  EXPECT_EQ(json["restarts"][0]["ended"], "signal 9");
  EXPECT_EQ(json["restarts"][0]["old_pid"], registration);
  EXPECT_EQ(json["services"]["registration"], 0);  // the restarted process stopped cleanly at the end
  EXPECT_GT(json["messages"]["twinslam/v3/registration"], 0);
  fs::remove_all(base);
}

// Issue 14: the estimator killed in flight and restarted by the run resumes from the checkpoint it left in the run's
// folder (resume.hpp) - in flight neither initialization may start a new process (steady flight; a constant-rate turn
// gives no scale). Realtime (in lockstep ingest would wait for the dead estimator); killed once its alignment was
// declared (the checkpoint exists) and a few seconds later. The run ends ok with the restart listed, the new process
// resumed, poses cover nearly every frame and the stretch outside W is short.
TEST(Run, AKilledEstimatorResumesFromItsCheckpoint) {
  const fs::path base = fs::temp_directory_path() / ("twinslam_run_resume_" + std::to_string(::getpid()));
  const auto sim = simulate_tiny(base);
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  test::Background run({test::bin("twinslam"), "run", (base / "tiny").string(), "--mode", "vio-twin", "--features",
                        "--realtime", "--restart", "estimator", "--out", (base / "run").string(), "--domain",
                        std::to_string(test::test_domain())});
  ASSERT_TRUE(twinslam::testing::wait_for([&] { return fs::exists(base / "run/estimator.checkpoint.json"); }, 90s))
      << run.output();
  std::this_thread::sleep_for(3s);
  const pid_t estimator = child_named(run.pid(), "twinslam-estima");
  ASSERT_GT(estimator, 0);
  ASSERT_EQ(::kill(estimator, SIGKILL), 0);
  ASSERT_EQ(run.wait(std::chrono::milliseconds(180'000)), 0) << run.output();
  std::ifstream in(base / "run/run.json");
  const auto json = nlohmann::json::parse(in);
  EXPECT_EQ(json["status"], "ok");
  ASSERT_EQ(json["restarts"].size(), 1u) << json.dump();
  EXPECT_EQ(json["restarts"][0]["service"], "estimator");
  EXPECT_EQ(json["counters"]["estimator"]["resumed_from_checkpoint"], 1) << json["counters"].dump();
  const double poses = json["poses"].get<double>(), frames = json["messages"]["twinslam/v1/features"].get<double>();
  EXPECT_GT(poses, 0.85 * frames) << json.dump();
  double outside_s = 0.0;
  for (const auto& span : json["out_of_world_ns"]) {
    outside_s += 1e-9 * static_cast<double>(span[1].get<std::int64_t>() - span[0].get<std::int64_t>());
  }
  std::printf("resumed: %.0f poses of %.0f frames, %.1f s outside W after the restart\n", poses, frames, outside_s);
  EXPECT_LT(outside_s, 10.0) << json["out_of_world_ns"].dump();
  fs::remove_all(base);
}

// Issue 14 (containers, docker/demo.sh): `twinslam run --external` leaves services to others and only waits for them.
// Started outside with the arguments the run would give them, they produce in lockstep the very trajectory the run
// makes when it starts them itself.
TEST(Run, ServicesStartedOutsideTheRunGiveTheSameLockstepTrajectory) {
  const fs::path base = fs::temp_directory_path() / ("twinslam_run_external_" + std::to_string(::getpid()));
  const fs::path tiny = base / "tiny";
  const auto sim = simulate_tiny(base);
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  std::ifstream yaml(tiny / "dataset.yaml");
  std::string line, origin;
  while (std::getline(yaml, line) && origin.empty()) {
    if (line.rfind("origin:", 0) != 0) continue;
    for (const char* key : {"lat:", "lon:", "alt:"}) {
      const auto at = line.find(key) + 4;
      // Appended piecewise: `const char* + std::string` here trips GCC 12's -Wrestrict false positive.
      if (!origin.empty()) origin += ',';
      origin += line.substr(at, line.find_first_of(",}", at) - at);
    }
  }
  ASSERT_FALSE(origin.empty());
  const auto store = test::run_process({test::bin("twinslam"), "twin", "build", (tiny / "twin/twin.ply").string(),
                                        "--origin", origin, "--out", (base / "store").string()});
  ASSERT_EQ(store.exit_code, 0) << store.err;
  const std::string domain = std::to_string(test::test_domain());
  const std::map<std::string, std::string> env{{"TWINSLAM_DOMAIN", domain}};
  const std::string cam = (tiny / "mav0/cam0/sensor.yaml").string(), imu = (tiny / "mav0/imu0/sensor.yaml").string();
  test::Background estimator({test::bin("twinslam-estimator"), "--vehicle", "uav0", "--max", "--camera", cam, "--imu",
                              imu, "--origin", origin, "--fuse-registrations", "--await-registration", "--align-gnss"},
                             env);
  test::Background tiles({test::bin("twinslam-tiles"), "--vehicle", "uav0", "--max", "--twin", (base / "store").string()},
                         env);
  test::Background registration({test::bin("twinslam-registration"), "--vehicle", "uav0", "--max"}, env);
  const auto outside = test::run_process({test::bin("twinslam"), "run", tiny.string(), "--mode", "vio-twin",
                                          "--features", "--no-progress", "--external", "estimator,tiles,registration",
                                          "--domain", domain, "--out", (base / "outside").string()},
                                         {}, std::chrono::seconds(180));
  ASSERT_EQ(outside.exit_code, 0) << outside.err;
  for (auto* p : {&estimator, &tiles, &registration}) p->signal(SIGINT);
  const auto own = test::run_process({test::bin("twinslam"), "run", tiny.string(), "--mode", "vio-twin", "--features",
                                      "--no-progress", "--domain", domain, "--out", (base / "own").string()},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(own.exit_code, 0) << own.err;
  const auto read = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const std::string trajectory = read(base / "outside/trajectory.tum");
  EXPECT_GT(std::count(trajectory.begin(), trajectory.end(), '\n'), 500);
  EXPECT_EQ(trajectory, read(base / "own/trajectory.tum"));
  const auto json = nlohmann::json::parse(read(base / "outside/run.json"));
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["external"], nlohmann::json({"estimator", "registration", "tiles"}));
  EXPECT_FALSE(json["services"].contains("estimator")) << json["services"].dump();  // the run started only ingest
  EXPECT_GT(json["messages"]["twinslam/v3/registration"], 0);
  fs::remove_all(base);
}

// A features-only dataset (`twinslam sim --no-images`: seconds instead of minutes of rendering) flies with
// `--features`, a pose for each of its feature frames; without `--features` the run refuses it in one line, before
// any service starts.
TEST(Run, AFeaturesOnlyDatasetFliesWithItsFeatureTracks) {
  const fs::path base = fs::temp_directory_path() / ("twinslam_run_features_only_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out",
                                      (base / "tiny").string(), "--features", "--no-images", "--quiet"},
                                     {}, std::chrono::seconds(120));
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  const std::string domain = std::to_string(test::test_domain());
  const auto refused = test::run_process({test::bin("twinslam"), "run", (base / "tiny").string(), "--mode", "vio",
                                          "--no-progress", "--domain", domain, "--out", (base / "images").string()});
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_NE(refused.err.find((base / "tiny/mav0/cam0/data.csv").string() +
                             ": no images listed (a features-only dataset: replay it with --features)"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(base / "images/run.json"));
  const auto run = test::run_process({test::bin("twinslam"), "run", (base / "tiny").string(), "--mode", "vio",
                                      "--features", "--no-progress", "--domain", domain, "--out",
                                      (base / "run").string()},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find(", 0 images, "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("601 feature frames (replayed)"), std::string::npos) << run.out;
  std::ifstream in(base / "run/trajectory.tum");
  const std::string trajectory((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_GT(std::count(trajectory.begin(), trajectory.end(), '\n'), 500);  // tiny: 601 frames in 30 s
  fs::remove_all(base);
}
