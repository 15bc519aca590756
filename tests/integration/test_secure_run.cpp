// `twinslam run --secure` (issue 14 item 5): the whole pipeline on tiny with DDS-Security (each process with its
// role's identity; files made on first use) gives the unsecured run's trajectory; during it, `twinslam echo` without
// a certificate hears nothing on the run's domain; an echo with the ops identity hears a secured edge service.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <csignal>

#include <nlohmann/json.hpp>

#include "subprocess.hpp"

namespace twinslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SecureRun, TheSecuredPipelineFliesTheSameAndAListenerWithoutCertificateHearsNothing) {
  const fs::path base = fs::temp_directory_path() / ("twinslam_secure_run_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out",
                                      (base / "tiny").string(), "--features", "--quiet"},
                                     {}, 120s);
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  auto run = [&](const std::string& name, int domain, bool secure) {
    std::vector<std::string> argv{test::bin("twinslam"), "run", (base / "tiny").string(), "--mode", "vio-twin",
                                  "--features", "--out", (base / name).string(), "--no-progress",
                                  "--domain", std::to_string(domain)};
    if (secure) argv.insert(argv.end(), {"--secure", "--security-dir", (base / "pki").string()});
    return test::run_process(argv, {}, 180s);
  };
  const int domain = test::test_domain();
  const auto plain = run("plain", domain, false);
  ASSERT_EQ(plain.exit_code, 0) << plain.out << plain.err;

  // A listener without a certificate on the secured run's domain, for the whole run: it must hear no Odometry.
  const std::string d = std::to_string(domain);
  test::Background uncertified({test::bin("twinslam"), "echo", "odometry", "--count", "1", "--timeout", "60",
                                "--domain", d});
  const auto secured = run("secured", domain, true);
  ASSERT_EQ(secured.exit_code, 0) << secured.out << secured.err;
  EXPECT_NE(secured.err.find("making DDS-Security files"), std::string::npos) << secured.err;
  ASSERT_TRUE(fs::is_regular_file(base / "pki/drone/permissions.p7s"));
  const auto json = nlohmann::json::parse(read_text(base / "secured/run.json"));
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["secure"], true);
  EXPECT_GT(json["messages"]["twinslam/v3/registration"], 0) << "the edge's registrations reached the drone";
  // Lockstep replay is deterministic: security changes nothing of what the estimator computes.
  EXPECT_EQ(read_text(base / "secured/trajectory.tum"), read_text(base / "plain/trajectory.tum"));
  uncertified.signal(SIGINT);
  EXPECT_EQ(uncertified.wait(10s), 1) << "a participant without a certificate received: " << uncertified.output();
  EXPECT_EQ(uncertified.output().find("stamp_ns"), std::string::npos) << uncertified.output();

  // The ops identity (monitors, `twinslam echo`) hears a secured service: the edge's registration, with the files the
  // run made (no new keys).
  test::Background edge({test::bin("twinslam-registration"), "--vehicle", "", "--profile", "twinslam.secure.edge",
                         "--security", (base / "pki").string()},
                        {{"TWINSLAM_DOMAIN", d}});
  const auto ops = test::run_process({test::bin("twinslam"), "echo", "heartbeat", "--count", "1", "--timeout", "30",
                                      "--domain", d, "--profile", "twinslam.secure.ops", "--security",
                                      (base / "pki").string()},
                                     {}, 60s);
  EXPECT_EQ(ops.exit_code, 0) << ops.err;
  EXPECT_NE(ops.out.find("registration"), std::string::npos) << ops.out;
  edge.signal(SIGINT);
  EXPECT_EQ(edge.wait(10s), 0) << edge.output();
  fs::remove_all(base);
}

}  // namespace
}  // namespace twinslam
