// The Foxglove bridge during a real tiny run (issue 16 item 1): `twinslam run --bridge PORT` starts twinslam-bridge
// with the pipeline, and a Foxglove WebSocket client (tests/node/bridge_client.mjs: @foxglove/ws-protocol over `ws`,
// the way Foxglove connects) subscribes to every advertised channel; every message it receives decodes with the OMG
// IDL schema its channel advertised (@foxglove/omgidl-*), and the run's streams reach it live — with the dataset's
// ground truth and its GNSS fixes in W next to the estimate (run passes the bridge --truth and --origin).
#include <unistd.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {

const fs::path& base() {
  static const fs::path dir = fs::temp_directory_path() / ("twinslam_bridge_" + std::to_string(::getpid()));
  return dir;
}

// The last line of the client's output: its JSON verdict.
nlohmann::json last_json_line(const std::string& output) {
  std::istringstream in(output);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty() && line.front() == '{') last = line;
  }
  return last.empty() ? nlohmann::json() : nlohmann::json::parse(last);
}

TEST(FoxgloveBridge, AClientSubscribedToEveryChannelDecodesTheRunLive) {
  fs::remove_all(base());
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out",
                                      (base() / "tiny").string(), "--features", "--quiet"},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  const std::string port = std::to_string(test::free_tcp_port());
  // Started first: it retries until the bridge listens, as an operator's Foxglove would.
  test::Background client({TWINSLAM_NODE, std::string(TWINSLAM_SOURCE_DIR) + "/tests/node/bridge_client.mjs",
                           "ws://127.0.0.1:" + port, "480"});
  const auto run = test::run_process({test::bin("twinslam"), "run", (base() / "tiny").string(), "--mode", "vio-twin",
                                      "--features", "--no-progress", "--bridge", port, "--out",
                                      (base() / "run").string(), "--domain", std::to_string(test::test_domain())},
                                     {}, std::chrono::seconds(420));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  ASSERT_EQ(client.wait(std::chrono::seconds(30)), 0) << client.output();  // the bridge closed: the client reports
  const nlohmann::json got = last_json_line(client.output());
  ASSERT_FALSE(got.is_null()) << client.output();
  EXPECT_EQ(got["server"], "twinslam-bridge");
  // Every topic of the table, and the well-known channels of the run's one vehicle and of the twin (bridge_client.mjs
  // validated each of their messages against Foxglove's own JSON Schemas).
  const std::map<std::string, std::string> well_known{
      {"/uav0/estimate/pose", "foxglove.PoseInFrame"},     {"/uav0/estimate/path", "foxglove.PosesInFrame"},
      {"/uav0/landmarks", "foxglove.PointCloud"},          {"/uav0/landmarks/registered", "foxglove.PointCloud"},
      {"/uav0/registration", "twinslam.RegistrationHealth"}, {"/twin/tiles", "foxglove.SceneUpdate"},
      {"/uav0/gnss", "foxglove.LocationFix"},          {"/uav0/gnss/path", "foxglove.PosesInFrame"},
      {"/uav0/truth/path", "foxglove.PosesInFrame"},    {"/services", "twinslam.ServiceState"}};
  EXPECT_EQ(got["channels"], 11 + well_known.size()) << got["schemas"].dump();
  for (const auto& [topic, schema] : well_known) {
    EXPECT_EQ(got["schemas"].value(topic, ""), schema) << topic;
    EXPECT_GT(got["counts"].value(topic, 0), 0) << topic << " in " << got.dump();
  }
  // What Foxglove's 3D panel draws: buildings (a tile's triangles) and a path that grew.
  const auto& tile = got["samples"]["/twin/tiles"]["entities"][0];
  EXPECT_GT(tile["triangles"][0]["indices"].value("length", 0), 0) << tile.dump();
  EXPECT_GT(got["counts"].value("/uav0/estimate/path", 0), 10);
  EXPECT_NE(std::find(got["vehicles"].begin(), got["vehicles"].end(), "uav0"), got["vehicles"].end()) << got.dump();
  for (const char* topic : {"twinslam/v1/imu", "twinslam/v1/features", "twinslam/v2/odometry", "twinslam/v2/local_map",
                            "twinslam/v3/registration", "twinslam/v1/heartbeat"}) {
    EXPECT_GT(got["counts"].value(topic, 0), 0) << topic << " in " << got.dump();
  }
  fs::remove_all(base());
}

}  // namespace
