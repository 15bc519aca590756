// CONTRACTS.md: `--max` lockstep replay gives the same trajectory on two runs of the same input. Runs the full
// image pipeline (ingest -> tracking -> estimator, separate processes) twice on a short simulated flight.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

TEST(RunCli, MaxReplayIsRepeatableThroughTheImagePipeline) {
  const fs::path base = fs::temp_directory_path() / ("twinslam_repeat_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--duration", "12",
                                      "--quiet", "--out", (base / "data").string()},
                                     {}, std::chrono::seconds(240));
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  std::string trajectories[2];
  for (int i = 0; i < 2; ++i) {
    const fs::path out = base / ("run" + std::to_string(i));
    const auto r = test::run_process({test::bin("twinslam"), "run", (base / "data").string(), "--mode", "vio", "--max",
                                      "--out", out.string()},
                                     {}, std::chrono::seconds(240));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    std::ifstream in(out / "trajectory.tum");
    std::stringstream ss;
    ss << in.rdbuf();
    trajectories[i] = ss.str();
  }
  EXPECT_GT(std::count(trajectories[0].begin(), trajectories[0].end(), '\n'), 150);
  EXPECT_EQ(trajectories[0], trajectories[1]);
  fs::remove_all(base);
}
