// Acceptance (issue 2): `twinslam launch deploy/local.yaml` runs five service processes, `twinslam topics` lists
// them, and one SIGINT (Ctrl-C) stops all of them within 2 s with exit code 0 and nothing of theirs left in /dev/shm.
#include <csignal>
#include <filesystem>
#include <set>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {
std::set<std::string> shm_files() {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator("/dev/shm")) out.insert(e.path().filename().string());
  return out;
}
}  // namespace

TEST(Launch, LocalDeploymentStartsListsAndStopsCleanly) {
  const auto shm_before = shm_files();
  const std::map<std::string, std::string> env{{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}};
  test::Background launch({test::bin("twinslam"), "launch", std::string(TWINSLAM_SOURCE_DIR) + "/deploy/local.yaml"},
                          env);
  std::set<std::string> services;
  nlohmann::json listing;
  for (int attempt = 0; attempt < 10 && services.size() < 5; ++attempt) {
    const auto topics = test::run_process({test::bin("twinslam"), "topics", "--json", "--window", "1.5"}, env);
    ASSERT_EQ(topics.exit_code, 0) << topics.err;
    listing = nlohmann::json::parse(topics.out);
    services.clear();
    for (const auto& s : listing["services"]) {
      if (s["state"] != "stopping") services.insert(s["service"].get<std::string>());
    }
  }
  EXPECT_EQ(services, (std::set<std::string>{"estimator", "ingest", "registration", "tiles", "tracking"}))
      << listing.dump(2) << "\n" << launch.output();
  // The live topics include the sensor streams ingest publishes.
  std::set<std::string> topic_names;
  for (const auto& t : listing["topics"]) topic_names.insert(t["name"].get<std::string>());
  EXPECT_TRUE(topic_names.count("twinslam/v1/heartbeat"));
  EXPECT_TRUE(topic_names.count("twinslam/v1/imu")) << listing.dump(2);

  const auto t0 = std::chrono::steady_clock::now();
  launch.signal(SIGINT);
  const int code = launch.wait(std::chrono::seconds(10));
  const double stop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(code, 0) << launch.output();
  EXPECT_LT(stop_s, 2.0) << launch.output();
  std::set<std::string> left;
  for (const auto& f : shm_files()) {
    if (shm_before.count(f) == 0) left.insert(f);
  }
  EXPECT_TRUE(left.empty()) << "left in /dev/shm: " << *left.begin();
}
