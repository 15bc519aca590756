// Acceptance (issue 2): each bad input ends with exit code 2 and a one-line reason naming the file and the problem.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>

#include "dataset_fixture.hpp"
#include "scratch_dir.hpp"
#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {
// Exit code 2 and exactly one line on stderr that contains every expected fragment.
void expect_bad_input(const test::ProcessOutput& r, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' not in: " << r.err;
}

test::ProcessOutput run_ingest(const fs::path& dataset) {
  return test::run_process({test::bin("twinslam-ingest"), "--dataset", dataset.string()},
                           {{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}});
}
}  // namespace

TEST(CliErrors, MissingDatasetFolder) {
  expect_bad_input(run_ingest("/nonexistent/ds"), {"/nonexistent/ds", "dataset folder does not exist"});
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", "/nonexistent/ds", "--mode", "vio", "--out",
                                      "/tmp/twinslam_never"}),
                   {"/nonexistent/ds", "does not exist"});
}

TEST(CliErrors, MalformedCsvRowNamesFileAndLine) {
  const auto dir = test::broken_copy("cli_badrow", [](const fs::path& d) {
    test::replace_line(d / "mav0/imu0/data.csv", 10, "1403715273307142912,0.1,0.2");
  });
  expect_bad_input(run_ingest(dir), {(dir / "mav0/imu0/data.csv").string() + ":10:", "expected 7 columns, found 3"});
}

TEST(CliErrors, TimestampsGoingBackwards) {
  const auto dir = test::broken_copy("cli_backwards", [](const fs::path& d) {
    test::replace_line(d / "mav0/imu0/data.csv", 5, "1403715273000000000,0.1,0.2,0.3,9.0,0.1,0.2");
  });
  expect_bad_input(run_ingest(dir), {(dir / "mav0/imu0/data.csv").string() + ":5:", "is not after the previous one"});
}

TEST(CliErrors, MissingImageFile) {
  const auto dir = test::broken_copy("cli_noimage", [](const fs::path& d) {
    fs::remove(d / "mav0/cam0/data/1403715275262142976.png");
  });
  expect_bad_input(run_ingest(dir), {"1403715275262142976.png", "does not exist", "cam0/data.csv:"});
}

TEST(CliErrors, UnknownParticipantProfile) {
  const auto r = test::run_process({test::bin("twinslam-tiles"), "--profile", "no.such.profile"},
                                   {{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}});
  expect_bad_input(r, {"twinslam.xml", "no participant profile named 'no.such.profile'"});
}

TEST(CliErrors, MissingQosFile) {
  const auto r = test::run_process({test::bin("twinslam-tiles"), "--qos", "/nonexistent/qos.xml"});
  expect_bad_input(r, {"/nonexistent/qos.xml", "QoS profile file not found"});
}

TEST(CliErrors, MalformedLaunchFile) {
  const fs::path f = test::scratch_dir() / "bad_launch.yaml";
  std::ofstream(f) << "services:\n  - name: a\n    exec: twinslam-tracking\n    argz: [1]\n";
  expect_bad_input(test::run_process({test::bin("twinslam"), "launch", f.string()}),
                   {f.string(), "unknown key 'services[0].argz'"});
  std::ofstream(f) << "services: [\n";
  expect_bad_input(test::run_process({test::bin("twinslam"), "launch", f.string()}), {f.string(), "invalid YAML"});
}

TEST(CliErrors, UnknownTopicForEcho) {
  expect_bad_input(test::run_process({test::bin("twinslam"), "echo", "nope"}), {"unknown topic 'nope'"});
}

namespace {
// A config file with `text` in a fresh folder (the folder doubles as a --config-dir).
fs::path config_dir_with(const std::string& name, const std::string& file, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("twinslam_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / file) << text;
  return dir;
}
const std::string kEuroc = std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro";
}  // namespace

TEST(CliErrors, BadServiceConfigNamesFileLineAndKey) {
  const std::map<std::string, std::string> env{{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}};
  const std::string camera = kEuroc + "/mav0/cam0/sensor.yaml", imu = kEuroc + "/mav0/imu0/sensor.yaml";
  const fs::path dir = config_dir_with("cfg_services", "estimator.yaml", "window_keyframes: 8\nwindow: 3\n");
  expect_bad_input(test::run_process({test::bin("twinslam-estimator"), "--camera", camera, "--imu", imu, "--config",
                                      (dir / "estimator.yaml").string()}, env),
                   {(dir / "estimator.yaml").string() + ":2:", "'window'", "unknown key"});
  std::ofstream(dir / "tracking.yaml") << "max_features: many\n";
  expect_bad_input(test::run_process({test::bin("twinslam-tracking"), "--camera", camera, "--config",
                                      (dir / "tracking.yaml").string()}, env),
                   {(dir / "tracking.yaml").string() + ":1:", "'max_features'", "expected an integer"});
  std::ofstream(dir / "ingest.yaml") << "ack_timeout_s: -1\n";
  expect_bad_input(test::run_process({test::bin("twinslam-ingest"), "--dataset", kEuroc, "--config",
                                      (dir / "ingest.yaml").string()}, env),
                   {(dir / "ingest.yaml").string(), "'ack_timeout_s'", "must lie in"});
  std::ofstream(dir / "tiles.yaml") << "window_m: [1\n";
  expect_bad_input(test::run_process({test::bin("twinslam-tiles"), "--no-twin", "--config",
                                      (dir / "tiles.yaml").string()}, env),
                   {(dir / "tiles.yaml").string() + ":", "malformed YAML"});
  expect_bad_input(test::run_process({test::bin("twinslam-estimator"), "--camera", camera, "--imu", imu, "--config",
                                      "/nonexistent/estimator.yaml"}, env),
                   {"/nonexistent/estimator.yaml", "cannot open file"});
  fs::remove_all(dir);
}

// --restart names services of the run; the estimator (or tracking) only with realtime replay, where no one waits
// for its acknowledgement of each frame. Refused before anything starts.
TEST(CliErrors, RunRefusesARestartItCannotHonour) {
  const std::string out = "/tmp/twinslam_restart_run_" + std::to_string(::getpid());
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--restart", "estimator"}),
                   {"--restart estimator needs --realtime", "acknowledgement"});
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--restart", "ingest"}),
                   {"--restart: 'ingest' is not a service of the run"});
  EXPECT_FALSE(fs::exists(out));
}

// --shared-edge joins an edge started outside the run: refused when the run could never meet it or be told apart
// from the fleet's other vehicles. Refused before anything starts.
TEST(CliErrors, RunRefusesASharedEdgeItCannotMeet) {
  const std::string out = "/tmp/twinslam_shared_run_" + std::to_string(::getpid());
  const std::string domain = std::to_string(test::test_domain());
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--shared-edge", "--domain",
                                      domain}),
                   {"--shared-edge: mode 'vio' uses no edge"});
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--mode", "vio-twin",
                                      "--shared-edge", "--domain", domain, "--vehicle", "uav*"}),
                   {"--shared-edge: the vehicle id 'uav*'", "no pattern"});
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--mode", "vio-twin",
                                      "--shared-edge", "--domain", domain, "--secure"}),
                   {"--shared-edge with --secure is not implemented"});
  if (std::getenv("TWINSLAM_DOMAIN") == nullptr) {
    expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--mode", "vio-twin",
                                        "--shared-edge"}),
                     {"--shared-edge: give the edge's DDS domain"});
  }
  EXPECT_FALSE(fs::exists(out));
}

// --external leaves services to containers or other hosts (docker/demo.sh): refused for a service the run does not
// have, and when it could never meet them. Refused before anything starts.
TEST(CliErrors, RunRefusesExternalServicesItCannotUseOrMeet) {
  const std::string out = "/tmp/twinslam_external_run_" + std::to_string(::getpid());
  const std::string domain = std::to_string(test::test_domain());
  const auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{test::bin("twinslam"), "run", kEuroc, "--out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::run_process(args);
  };
  expect_bad_input(run({"--external", "ingest", "--domain", domain}),
                   {"--external: 'ingest' is not a service the run can leave to others"});
  expect_bad_input(run({"--external", "tracking", "--features", "--domain", domain}),
                   {"--external tracking: with --features the run has no tracking"});
  expect_bad_input(run({"--external", "registration", "--domain", domain}),
                   {"--external registration: mode 'vio' uses no registration"});
  expect_bad_input(run({"--external", "tiles", "--mode", "vio-twin", "--shared-edge", "--domain", domain}),
                   {"--external and --shared-edge"});
  if (std::getenv("TWINSLAM_DOMAIN") == nullptr) {
    expect_bad_input(run({"--external", "estimator"}), {"--external: give the DDS domain"});
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, RunWithABadConfigDirStopsWithTheServicesLine) {
  const std::string out = "/tmp/twinslam_cfg_run_" + std::to_string(::getpid());
  const std::string domain = std::to_string(test::test_domain());
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--domain", domain,
                                      "--config-dir", "/nonexistent/config"}),
                   {"/nonexistent/config", "config directory does not exist"});
  // The estimator rejects its file during start-up: run ends with exit 2 and the estimator's own line.
  const fs::path dir = config_dir_with("cfg_run", "estimator.yaml", "motion_init:\n  window_s: long\n");
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", kEuroc, "--out", out, "--domain", domain,
                                      "--config-dir", dir.string()}, {}, std::chrono::seconds(60)),
                   {"estimator: " + (dir / "estimator.yaml").string() + ":2:", "'motion_init.window_s'",
                    "expected a number [s]"});
  fs::remove_all(dir);
  fs::remove_all(out);
}
