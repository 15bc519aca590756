// What `twinslam run` takes from --config-dir and what it says when a service fails (tools/twinslam/run_config_dir.hpp).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "run_config_dir.hpp"

namespace twinslam::cli {
namespace {

namespace fs = std::filesystem;

class RunConfigDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twinslam_runcfg_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }

  fs::path dir_;
};

// The run gives ingest its own start-up budget unless the user's ingest.yaml names one.
TEST_F(RunConfigDir, AKeyCountsAsSetOnlyWhenTheServicesFileNamesIt) {
  EXPECT_FALSE(config_sets_key("", "ingest", "start_timeout_s"));
  EXPECT_FALSE(config_sets_key(dir_.string(), "ingest", "start_timeout_s"));  // no ingest.yaml
  write("ingest.yaml", "speed: 2.0\n");
  EXPECT_FALSE(config_sets_key(dir_.string(), "ingest", "start_timeout_s"));
  write("ingest.yaml", "speed: 2.0\nstart_timeout_s: 5  # [s]\n");
  EXPECT_TRUE(config_sets_key(dir_.string(), "ingest", "start_timeout_s"));
  EXPECT_FALSE(config_sets_key(dir_.string(), "estimator", "start_timeout_s"));
}

// Each service that ended badly is named with how it ended and its own last error line, so a failed run says why
// without opening the logs; services that exited 0 are not listed.
TEST_F(RunConfigDir, FailedServicesAreNamedWithTheirOwnErrorLine) {
  write("ingest.log", "06:04:14.729 info dataset ...\ntwinslam-ingest: no consumer ready within 60000 ms (matched "
                      "readers: imu 2/3)\n");
  write("estimator.log", "twinslam-estimator: internal error: earlier\n");
  process::ChildResult ingest{"ingest", 11, 1, std::nullopt};
  process::ChildResult estimator{"estimator", 12, 0, std::nullopt};
  process::ChildResult tiles{"tiles", 13, std::nullopt, 9};
  const auto lines = failed_service_lines({ingest, estimator, tiles}, dir_);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "ingest (exit code 1): no consumer ready within 60000 ms (matched readers: imu 2/3)");
  EXPECT_EQ(lines[1], "tiles (signal 9): see " + (dir_ / "tiles.log").string());
  EXPECT_TRUE(failed_service_lines({estimator}, dir_).empty());
}

}  // namespace
}  // namespace twinslam::cli
