// The drone-edge link (issue 14 items 3 and 5), each case a tiny vio-twin run in lockstep compared with the same run
// on one host (made once, shared by the cases under a file lock): the pipeline under DDS-Security (`run --secure`)
// while a listener without a certificate hears nothing, and the drone and the edge in network namespaces of their own
// over a veth link (scripts/two-hosts.sh), discovering through initial peers or a discovery server. Each must fly as
// well as the one-host run: ATE in W within 1.2x (issue 14). Not to the byte: lockstep waits for a registration only
// up to a timeout, so on a loaded machine a result can be fused a keyframe later (seen in CI with the secured run).
// The link is also run with 10 % loss and 100 ms delay each way (two-hosts.sh --netem), and two vehicles share one
// edge (scripts/fleet.sh).
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <regex>
#include <vector>

#include <nlohmann/json.hpp>

#include "file_lock.hpp"
#include "subprocess.hpp"
#include "text_file.hpp"

namespace twinslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const fs::path kWork = TWINSLAM_LINK_WORK_DIR;

// The tiny dataset and its one-host vio-twin run, once per build of the executables.
fs::path reference_run() {
  fs::create_directories(kWork);
  test::FileLock lock(kWork / "lock");
  std::string stamp;
  for (const char* exe : {"twinslam", "twinslam-estimator", "twinslam-registration", "twinslam-tiles"}) {
    stamp += std::to_string(fs::last_write_time(test::bin(exe)).time_since_epoch().count()) + " ";
  }
  if (test::read_text(kWork / "stamp") != stamp) {
    fs::remove_all(kWork / "tiny");
    fs::remove_all(kWork / "one-host");
    const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out",
                                        (kWork / "tiny").string(), "--features", "--quiet"}, {}, 180s);
    if (sim.exit_code != 0) throw std::runtime_error("sim tiny failed: " + sim.out + sim.err);
    const auto run = test::run_process({test::bin("twinslam"), "run", (kWork / "tiny").string(), "--mode", "vio-twin",
                                        "--features", "--out", (kWork / "one-host").string(), "--no-progress",
                                        "--domain", std::to_string(test::test_domain())}, {}, 180s);
    if (run.exit_code != 0) throw std::runtime_error("the one-host run failed: " + run.out + run.err);
    std::ofstream(kWork / "stamp") << stamp;
  }
  return kWork / "one-host";
}

nlohmann::json run_json(const fs::path& run) { return nlohmann::json::parse(test::read_text(run / "run.json")); }

// Position ATE RMSE in W, no alignment (twinslam eval --align none).
double ate_in_w(const fs::path& run) {
  const auto e = test::run_process({test::bin("twinslam"), "eval", "--est", run.string(), "--gt",
                                    (kWork / "tiny").string(), "--align", "none", "--json"}, {}, 60s);
  if (e.exit_code != 0) throw std::runtime_error("twinslam eval failed: " + e.out + e.err);
  return nlohmann::json::parse(e.out).at("ate_pos_rmse_m").get<double>();
}

// As well as the one-host run: ATE in W within 1.2x of it.
void expect_flies_as_well_as(const fs::path& run, const fs::path& reference) {
  const double ate = ate_in_w(run), one_host = ate_in_w(reference);
  EXPECT_GT(ate, 0.0);
  EXPECT_LE(ate, 1.2 * one_host) << "ATE in W " << ate << " m, one host " << one_host << " m";
}

TEST(DroneEdgeLink, TheSecuredPipelineFliesTheSameAndAListenerWithoutCertificateHearsNothing) {
  const fs::path reference = reference_run();
  const fs::path base = kWork / ("secured-" + std::to_string(::getpid()));
  fs::remove_all(base);
  const std::string d = std::to_string(test::test_domain());
  // A listener without a certificate on the secured run's domain, for the whole run: it must hear no Odometry.
  test::Background uncertified({test::bin("twinslam"), "echo", "odometry", "--count", "1", "--timeout", "60",
                                "--domain", d});
  const auto secured = test::run_process({test::bin("twinslam"), "run", (kWork / "tiny").string(), "--mode",
                                          "vio-twin", "--features", "--out", (base / "run").string(), "--no-progress",
                                          "--domain", d, "--secure", "--security-dir", (base / "pki").string()},
                                         {}, 180s);
  ASSERT_EQ(secured.exit_code, 0) << secured.out << secured.err;
  EXPECT_NE(secured.err.find("making DDS-Security files"), std::string::npos) << secured.err;
  ASSERT_TRUE(fs::is_regular_file(base / "pki/drone/permissions.p7s"));
  const auto json = run_json(base / "run");
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["secure"], true);
  EXPECT_GT(json["messages"]["twinslam/v3/registration"], 0) << "the edge's registrations reached the drone";
  expect_flies_as_well_as(base / "run", reference);
  uncertified.signal(SIGINT);
  EXPECT_EQ(uncertified.wait(10s), 1) << "a participant without a certificate received: " << uncertified.output();
  EXPECT_EQ(uncertified.output().find("stamp_ns"), std::string::npos) << uncertified.output();

  // The ops identity (monitors, `twinslam echo`) hears a secured edge service with the files the run made.
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

// Network namespaces need root (CAP_NET_ADMIN); elsewhere the case is skipped, saying so.
bool can_make_namespaces() {
  const std::string probe = "tw-probe-" + std::to_string(::getpid());
  const auto made = test::run_process({"/bin/sh", "-c", "ip netns add " + probe + " && ip netns del " + probe}, {}, 20s);
  return made.exit_code == 0;
}

// Runs scripts/two-hosts.sh on the tiny dataset with `link_options` (discovery, impairment); returns its output.
std::string run_two_hosts(const fs::path& out, const std::vector<std::string>& link_options) {
  std::vector<std::string> command = {"/bin/bash", std::string(TWINSLAM_SOURCE_DIR) + "/scripts/two-hosts.sh",
                                      (kWork / "tiny").string(), out.string()};
  command.insert(command.end(), link_options.begin(), link_options.end());
  command.push_back("--features");
  const auto r = test::run_process(command, {{"TWINSLAM_BIN", fs::path(test::bin("twinslam")).parent_path().string()}},
                                   240s);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return r.out;
}

void expect_two_hosts_fly_as_one(const std::string& discovery) {
  if (!can_make_namespaces()) GTEST_SKIP() << "no network namespaces here (needs root and iproute2)";
  const fs::path reference = reference_run();
  const fs::path out = kWork / (discovery + "-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string output = run_two_hosts(out, {"--discovery", discovery});
  ASSERT_FALSE(::testing::Test::HasFailure());
  // What crossed the veth: the drone's LocalMaps one way, the edge's tiles and registrations the other.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(output, m, std::regex("link carried (\\d+) bytes drone -> edge and (\\d+) bytes")))
      << output;
  EXPECT_GT(std::stod(m[1]), 1e6);
  EXPECT_GT(std::stod(m[2]), 1e6);
  const auto json = run_json(out / "run");
  EXPECT_EQ(json["status"], "ok");
  EXPECT_TRUE(json["edge_netns"].is_string());
  EXPECT_GT(json["counters"]["registration"].value("local_maps_in", 0), 50) << "LocalMaps received on the edge";
  EXPECT_GT(json["counters"]["estimator"].value("registrations_fused", 0), 5) << "registrations fused on the drone";
  expect_flies_as_well_as(out / "run", reference);
  fs::remove_all(out);
}

TEST(DroneEdgeLink, TwoHostsDiscoveringThroughInitialPeersFlyAsOne) { expect_two_hosts_fly_as_one("peers"); }

TEST(DroneEdgeLink, TwoHostsDiscoveringThroughADiscoveryServerFlyAsOne) { expect_two_hosts_fly_as_one("server"); }

// 10 % loss and 100 ms delay each way (issue 14's link fault, through twinslam-netem): the registrations still arrive,
// each is fused on the keyframe whose stamp it carries (none unknown, none moved to another), and the run flies as
// well as on one host.
TEST(DroneEdgeLink, OverALossyDelayedLinkRegistrationsAreFusedOnTheirOwnKeyframes) {
  if (!can_make_namespaces()) GTEST_SKIP() << "no network namespaces here (needs root and iproute2)";
  const fs::path reference = reference_run();
  const fs::path out = kWork / ("lossy-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string output = run_two_hosts(out, {"--netem", "10", "100"});
  ASSERT_FALSE(::testing::Test::HasFailure());
  // The impairment acted both ways: about a tenth of the packets lost.
  const std::regex direction("netem \\S+ -> \\S+ in (\\d+) \\(lost (\\d+),");
  int directions = 0;
  for (std::sregex_iterator it(output.begin(), output.end(), direction), end; it != end; ++it, ++directions) {
    const double in = std::stod((*it)[1]), lost = std::stod((*it)[2]);
    EXPECT_GT(in, 1000.0);
    EXPECT_NEAR(lost / in, 0.10, 0.03) << it->str();
  }
  EXPECT_EQ(directions, 2) << output;
  const auto json = run_json(out / "run");
  EXPECT_EQ(json["status"], "ok");
  const auto& estimator = json["counters"]["estimator"];
  EXPECT_GT(estimator.value("registrations_fused", 0), 5) << estimator;
  EXPECT_EQ(estimator.value("registrations_unknown_keyframe", 0), 0) << estimator;
  EXPECT_EQ(estimator.value("registrations_reattached", 0), 0) << estimator;
  EXPECT_GT(json["registration_latency_ms"]["median"].get<double>(), 150.0) << "200 ms of round trip on the path";
  expect_flies_as_well_as(out / "run", reference);
  fs::remove_all(out);
}

// A fleet on one edge (issue 14 item 6, scripts/fleet.sh --split): the tiny dataset flown at once as uav0 and uav1 in
// lockstep, each vehicle's processes in its own DDS partition, one tiles service and two registration instances in
// the partitions "uav0,edge" and "uav1,edge". Each vehicle flies as well as alone and each instance serves only its
// vehicle: DDS routes the LocalMaps, no instance filters.
TEST(DroneEdgeLink, TwoVehiclesShareOneEdgeEachServedByItsOwnRegistrationInstance) {
  const fs::path reference = reference_run();
  const fs::path out = kWork / ("fleet-" + std::to_string(::getpid()));
  const std::string tiny = (kWork / "tiny").string();
  const auto r = test::run_process({"/bin/bash", std::string(TWINSLAM_SOURCE_DIR) + "/scripts/fleet.sh", out.string(),
                                    tiny, tiny, "--split", "--max", "--", "--features"},
                                   {{"TWINSLAM_BIN", fs::path(test::bin("twinslam")).parent_path().string()},
                                    {"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}},
                                   300s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto fleet = nlohmann::json::parse(test::read_text(out / "fleet.json"));
  ASSERT_EQ(fleet["vehicles"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const auto& v = fleet["vehicles"][k];
    EXPECT_EQ(v["status"], "ok") << v;
    EXPECT_GT(v["fused"].get<int>(), 5) << v;
    expect_flies_as_well_as(out / ("uav" + std::to_string(k)), reference);
  }
  const auto& served = fleet["served"];
  ASSERT_EQ(served.size(), 2u) << served;
  ASSERT_EQ(served["registration-a"].size(), 1u) << "registration-a served " << served["registration-a"];
  ASSERT_EQ(served["registration-b"].size(), 1u) << "registration-b served " << served["registration-b"];
  EXPECT_GT(served["registration-a"].value("uav0", 0), 50) << served;
  EXPECT_GT(served["registration-b"].value("uav1", 0), 50) << served;
  EXPECT_GT(fleet["edge"]["tiles"]["peak_rss_mb"].get<double>(), 0.0);
  fs::remove_all(out);
}

}  // namespace
}  // namespace twinslam
