// `twinslam bench` end to end on a short simulated flight with ideal tracks: every requested mode is run and
// evaluated, table.md has the paper's Table I rows, metrics.json the eval keys, and the plots exist. The VIO
// estimate must be within 1 % of the path length (posyaw) — the estimator's own tests hold it to tighter bounds.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

TEST(BenchCli, TinyFlightTableMetricsAndPlots) {
  const fs::path data = fs::temp_directory_path() / ("twinslam_bench_data_" + std::to_string(::getpid()));
  const fs::path out = fs::temp_directory_path() / ("twinslam_bench_out_" + std::to_string(::getpid()));
  fs::remove_all(data);
  fs::remove_all(out);
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--duration", "15",
                                      "--features", "--quiet", "--out", data.string()},
                                     {}, std::chrono::seconds(240));
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto bench = test::run_process({test::bin("twinslam"), "bench", data.string(), "--out", out.string(),
                                        "--modes", "vio", "--features"},
                                       {}, std::chrono::seconds(300));
  ASSERT_EQ(bench.exit_code, 0) << bench.out << bench.err;
  // Progress per mode on stderr, plain lines when not a terminal (as here), ending at every frame done.
  EXPECT_TRUE(std::regex_search(bench.err, std::regex(R"(\nvio +\[#{30}\] 100% (\d+)/\1 .*ETA 0s\n)"))) << bench.err;
  std::ifstream table_in(out / "table.md");
  std::stringstream table;
  table << table_in.rdbuf();
  for (const char* row : {"| ATE_p [m] |", "| ATE_R [deg] |", "| per-frame time, median [ms] |", "vio (posyaw)"}) {
    EXPECT_NE(table.str().find(row), std::string::npos) << row << " missing in\n" << table.str();
  }
  std::ifstream metrics_in(out / "metrics.json");
  const auto metrics = nlohmann::json::parse(metrics_in);
  ASSERT_TRUE(metrics.contains("vio"));
  const auto& vio = metrics["vio"];
  EXPECT_EQ(vio["align"], "posyaw");
  const double length = vio["length_m"], ate = vio["ate_pos_rmse_m"];
  EXPECT_GT(length, 20.0);
  EXPECT_LT(ate, 0.01 * length) << "ATE " << ate << " m on " << length << " m";
  for (const char* png : {"trajectory_xy.png", "trajectory_xz.png", "error_position.png"}) {
    EXPECT_TRUE(fs::exists(out / png)) << png;
  }
  fs::remove_all(data);
  fs::remove_all(out);
}

// A mode the dataset cannot run (the EuRoC excerpt has no GNSS, origin or twin) is noted in the table and the others
// still run; when nothing can run, exit 2.
TEST(BenchCli, ModesTheDatasetCannotRunAreNotedNotFatal) {
  const std::string euroc = std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro";
  const fs::path out = fs::temp_directory_path() / ("twinslam_bench_notrun_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto both = test::run_process(
      {test::bin("twinslam"), "bench", euroc, "--out", out.string(), "--modes", "vio,vio-gnss"}, {},
      std::chrono::seconds(300));
  ASSERT_EQ(both.exit_code, 0) << both.out << both.err;
  std::ifstream in(out / "table.md");
  std::stringstream table;
  table << in.rdbuf();
  EXPECT_NE(table.str().find("vio (posyaw)"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("Not run on this dataset: vio-gnss (mode 'vio-gnss': the dataset has no GNSS"),
            std::string::npos) << table.str();
  const auto none = test::run_process(
      {test::bin("twinslam"), "bench", euroc, "--out", out.string(), "--modes", "vio-gnss"}, {},
      std::chrono::seconds(120));
  EXPECT_EQ(none.exit_code, 2) << none.out << none.err;
  fs::remove_all(out);
}
