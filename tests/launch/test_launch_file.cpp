// Launch files: the shipped deployments parse and name executables that the build produces; environment
// defaults are expanded; relative working folders resolve against the launch file's folder.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "launch_file.hpp"
#include "scratch_dir.hpp"
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
  const fs::path f = test::scratch_dir() / "launch.yaml";
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
  EXPECT_EQ(s.cwd, test::scratch_dir() / "sub");
}

TEST(LaunchFile, RejectsDuplicateNamesAndEmptyLists) {
  const fs::path f = test::scratch_dir() / "launch_dup.yaml";
  std::ofstream(f) << "services:\n  - {name: a, exec: x}\n  - {name: a, exec: y}\n";
  EXPECT_THROW(cli::load_launch_file(f), InputError);
  std::ofstream(f) << "services: []\n";
  EXPECT_THROW(cli::load_launch_file(f), InputError);
  EXPECT_THROW(cli::load_launch_file("/nonexistent.yaml"), InputError);
}

// Issue 14: `restart: on-failure` (the shipped edge services) and `max_restarts`; a wrong value is named.
TEST(LaunchFile, RestartPolicyIsReadAndTheEdgeServicesHaveIt) {
  const auto edge = cli::load_launch_file(fs::path(TWINSLAM_SOURCE_DIR) / "deploy/edge.yaml");
  for (const auto& s : edge.services) EXPECT_TRUE(s.restart_on_failure) << s.name;
  const auto drone = cli::load_launch_file(fs::path(TWINSLAM_SOURCE_DIR) / "deploy/drone.yaml");
  for (const auto& s : drone.services) EXPECT_FALSE(s.restart_on_failure) << s.name;
  const fs::path f = test::scratch_dir() / "launch_restart.yaml";
  std::ofstream(f) << "name: t\nservices:\n  - {name: s, exec: x, restart: on-failure, max_restarts: 2}\n";
  const auto launch = cli::load_launch_file(f);
  EXPECT_TRUE(launch.services[0].restart_on_failure);
  EXPECT_EQ(launch.services[0].max_restarts, 2);
  std::ofstream(f) << "name: t\nservices:\n  - {name: s, exec: x, restart: always}\n";
  try {
    cli::load_launch_file(f);
    FAIL() << "restart: always was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("services[0].restart"), std::string::npos) << e.what();
  }
  fs::remove(f);
}
