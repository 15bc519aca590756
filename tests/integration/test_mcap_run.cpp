// MCAP recordings of a real tiny run (issue 16 item 3): `twinslam run --mcap` writes RUN/run.mcap and a
// `twinslam record` on the run's domain records the same topics; both are read back by the official MCAP reader
// (@mcap/core, indexed and streamed with CRCs) and every message is decoded with its advertised OMG IDL schema
// (@foxglove/omgidl-*), in tests/node/run_mcap.mjs: every channel, message counts equal to the run's own counts.
#include <csignal>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "text_file.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {

const fs::path& base() {
  static const fs::path dir = fs::temp_directory_path() / ("twinslam_mcap_" + std::to_string(::getpid()));
  return dir;
}

// The Node checker's verdict on one recording: its JSON line, or a failure with what it printed.
nlohmann::json read_back(const fs::path& run, const fs::path& file, bool at_least) {
  std::vector<std::string> argv{TWINSLAM_NODE, std::string(TWINSLAM_SOURCE_DIR) + "/tests/node/run_mcap.mjs",
                                run.string(), file.string()};
  if (at_least) argv.push_back("--at-least");
  const auto r = test::run_process(argv, {}, std::chrono::seconds(120));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  if (r.exit_code != 0) return nlohmann::json();
  // Node's test runner reports on stdout too (TAP): the verdict is the line that is a JSON object.
  std::istringstream out(r.out);
  for (std::string line; std::getline(out, line);) {
    if (!line.empty() && line.front() == '{') return nlohmann::json::parse(line);
  }
  ADD_FAILURE() << "no JSON verdict in: " << r.out;
  return nlohmann::json();
}

// Rows of a EuRoC data.csv (header and comments left out).
int data_rows(const fs::path& csv) {
  std::istringstream in(test::read_text(csv));
  int rows = 0;
  for (std::string line; std::getline(in, line);) rows += !line.empty() && line[0] != '#';
  return rows;
}

TEST(McapRecording, ATinyRunAndARecordOfItReadBackWithTheOfficialReaders) {
  fs::remove_all(base());
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out",
                                      (base() / "tiny").string(), "--features", "--quiet"},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  const std::string domain = std::to_string(test::test_domain());
  test::Background record({test::bin("twinslam"), "record", (base() / "record.mcap").string(), "--domain", domain});
  const auto run = test::run_process({test::bin("twinslam"), "run", (base() / "tiny").string(), "--mode", "vio-twin",
                                      "--features", "--no-progress", "--mcap", "--out", (base() / "run").string(),
                                      "--domain", domain, "--extra-readers", "1"},
                                     {}, std::chrono::seconds(420));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  record.signal(SIGINT);
  ASSERT_EQ(record.wait(std::chrono::seconds(30)), 0) << record.output();

  const auto run_json = nlohmann::json::parse(test::read_text(base() / "run/run.json"));
  ASSERT_TRUE(run_json.contains("mcap")) << run_json.dump(1);
  EXPECT_EQ(run_json["mcap"]["file"], "run.mcap");
  for (const fs::path& file : {base() / "run/run.mcap", base() / "record.mcap"}) {
    SCOPED_TRACE(file.string());
    // run.mcap holds exactly what the run counted; the record at least that (run_mcap.mjs --at-least) and, lockstep
    // being lossless for every reliable reader, every IMU sample and camera frame of the dataset.
    const bool is_record = file.filename() == "record.mcap";
    const nlohmann::json got = read_back(base() / "run", file, is_record);
    ASSERT_FALSE(got.is_null());
    // Every topic of the table, used or not, and the well-known JSON channels the bridge serves (run_mcap.mjs
    // validated their messages against Foxglove's own schemas).
    std::map<std::string, std::string> well_known{
        {"/uav0/estimate/pose", "foxglove.PoseInFrame"}, {"/uav0/estimate/path", "foxglove.PosesInFrame"},
        {"/uav0/landmarks", "foxglove.PointCloud"},      {"/uav0/registration", "twinslam.RegistrationHealth"},
        {"/twin/tiles", "foxglove.SceneUpdate"},         {"/uav0/gnss", "foxglove.LocationFix"},
        {"/services", "twinslam.ServiceState"}};
    if (!is_record) {  // the run knows its dataset: the truth and the GNSS fixes in W are recorded too
      well_known["/uav0/truth/path"] = "foxglove.PosesInFrame";
      well_known["/uav0/gnss/path"] = "foxglove.PosesInFrame";
    }
    EXPECT_GE(got["channels"].get<std::size_t>(), 11 + well_known.size()) << got["schemas"].dump();
    for (const auto& [topic, schema] : well_known) {
      EXPECT_EQ(got["schemas"].value(topic, ""), schema) << topic;
      EXPECT_GT(got["counts"].value(topic, 0), 0) << topic;
    }
    EXPECT_EQ(got["vehicles"], nlohmann::json::array({"uav0"}));
    EXPECT_GT(got["chunks"].get<int>(), 1);
    // The run's streams, each with messages: what Foxglove would show of a vio-twin run.
    for (const char* topic : {"twinslam/v1/imu", "twinslam/v1/features", "twinslam/v2/odometry",
                              "twinslam/v2/local_map", "twinslam/v3/registration", "twinslam/v1/map_tile"}) {
      EXPECT_GT(got["counts"].value(topic, 0), 0) << topic << " in " << got.dump();
    }
    if (is_record) {
      EXPECT_EQ(got["counts"].value("twinslam/v1/imu", 0), data_rows(base() / "tiny/mav0/imu0/data.csv"));
      EXPECT_EQ(got["counts"].value("twinslam/v1/features", 0), data_rows(base() / "tiny/mav0/cam0/data.csv"));
    }
  }
  fs::remove_all(base());
}

}  // namespace
