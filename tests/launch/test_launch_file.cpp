// Launch files: the shipped deployments parse and name executables that the build produces; environment
// defaults are expanded; relative working folders resolve against the launch file's folder.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "launch_file.hpp"
#include "twinslam/core/error.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

TEST(LaunchFile, ShippedDeploymentsParseAndTheirExecutablesExist) {
  for (const char* name : {"local.yaml", "drone.yaml", "edge.yaml"}) {
    const auto launch = cli::load_launch_file(fs::path(TWINSLAM_SOURCE_DIR) / "deploy" / name);
    ASSERT_FALSE(launch.services.empty()) << name;
    for (const auto& s : launch.services) {
      EXPECT_TRUE(fs::exists(fs::path(TWINSLAM_BIN_DIR) / s.exec)) << name << ": " << s.exec;
      EXPECT_EQ(s.cwd, fs::path(TWINSLAM_SOURCE_DIR) / "deploy");
    }
  }
  const auto local = cli::load_launch_file(fs::path(TWINSLAM_SOURCE_DIR) / "deploy/local.yaml");
  EXPECT_EQ(local.services.size(), 5u);
}

TEST(LaunchFile, ExpandsEnvironmentDefaultsAndOverrides) {
  const fs::path f = fs::temp_directory_path() / ("twinslam_launch_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(f) << "name: t\nenv: {A: \"${TWINSLAM_T_UNSET:-one}\"}\nservices:\n"
                      "  - {name: s, exec: x, args: [\"${TWINSLAM_T_SET}\"], env: {B: two}, required: true, cwd: sub}\n";
  ::setenv("TWINSLAM_T_SET", "val", 1);
  const auto launch = cli::load_launch_file(f);
  ASSERT_EQ(launch.services.size(), 1u);
  const auto& s = launch.services[0];
  EXPECT_EQ(s.args, std::vector<std::string>{"val"});
  EXPECT_EQ(s.env.at("A"), "one");
  EXPECT_EQ(s.env.at("B"), "two");
  EXPECT_TRUE(s.required);
  EXPECT_EQ(s.cwd, fs::temp_directory_path() / "sub");
}

TEST(LaunchFile, RejectsDuplicateNamesAndEmptyLists) {
  const fs::path f = fs::temp_directory_path() / ("twinslam_launch_dup_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(f) << "services:\n  - {name: a, exec: x}\n  - {name: a, exec: y}\n";
  EXPECT_THROW(cli::load_launch_file(f), InputError);
  std::ofstream(f) << "services: []\n";
  EXPECT_THROW(cli::load_launch_file(f), InputError);
  EXPECT_THROW(cli::load_launch_file("/nonexistent.yaml"), InputError);
}
