// The `eval` subcommand end to end through the test driver: exit codes, one JSON object, messages, plots.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "twinslam/trajectory/io.hpp"

namespace twinslam {
namespace {
namespace fs = std::filesystem;

struct Outcome {
  int code = -1;
  std::string out, err;
};

class EvalCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twinslam_test_eval_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Estimate: the micro ground truth shifted 0.1 m in x, as a run folder.
    Trajectory est = read_dataset_groundtruth(micro_);
    for (auto& pose : est.poses) pose.T_XB.translation().x() += 0.1;
    fs::create_directories(dir_ / "run");
    write_tum(dir_ / "run" / "trajectory.tum", est);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Outcome run(const std::string& args) {
    const std::string cmd = std::string(TWINSLAM_BIN_DIR) + "/eval_cli_driver eval " + args + " >" +
                            (dir_ / "out.txt").string() + " 2>" + (dir_ / "err.txt").string();
    const int status = std::system(cmd.c_str());
    Outcome o;
    o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.out = slurp(dir_ / "out.txt");
    o.err = slurp(dir_ / "err.txt");
    return o;
  }
  static std::string slurp(const fs::path& p) {
    std::stringstream ss;
    ss << std::ifstream(p).rdbuf();
    return ss.str();
  }

  const std::string micro_ = std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro";
  fs::path dir_;
};

TEST_F(EvalCli, JsonIsOneObjectWithTheContractKeys) {
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "run").string() + " --json");
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);  // throws if stdout holds anything but one JSON value
  ASSERT_TRUE(j.is_object());
  for (const char* key : {"align", "n", "length_m", "ate_pos_rmse_m", "ate_rot_rmse_deg", "ate_pos_max_m", "rpe"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["align"], "none");
  EXPECT_EQ(j["n"], 2895);
  EXPECT_NEAR(j["ate_pos_rmse_m"].get<double>(), 0.1, 1e-9);
  EXPECT_NEAR(j["ate_pos_max_m"].get<double>(), 0.1, 1e-9);
  ASSERT_TRUE(j["rpe"].contains("50m"));
  EXPECT_TRUE(j["rpe"]["50m"].contains("trans_pct"));
  EXPECT_TRUE(j["rpe"]["50m"].contains("rot_deg_per_m"));
  EXPECT_NEAR(j["rpe"]["10m"]["trans_pct"].get<double>(), 0.0, 1e-9);  // a constant offset has no relative error
}

TEST_F(EvalCli, HumanOutputIsATable) {
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "run").string() + " --align se3");
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("align se3"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("pos [m]"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("50m"), std::string::npos) << o.out;
}

TEST_F(EvalCli, UnmatchedStampsExitTwoWithAReason) {
  std::ofstream(dir_ / "far.tum") << "100.0 0 0 0 0 0 0 1\n100.1 0 0 0 0 0 0 1\n";
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "far.tum").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("no estimate pose within 20 ms"), std::string::npos) << o.err;
  EXPECT_TRUE(o.out.empty()) << o.out;
}

TEST_F(EvalCli, EmptyFileExitsTwoNamingIt) {
  std::ofstream(dir_ / "empty.tum") << "# timestamp tx ty tz qx qy qz qw\n";
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "empty.tum").string() + " --json");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("empty.tum: no poses"), std::string::npos) << o.err;
}

// A world-frame run (vio-twin) is in L before its alignment is declared: without --align, eval compares only the poses
// from run.json's aligned_from_stamp_ns on, as bench does, and says so; a broken run.json is named.
TEST_F(EvalCli, AWorldFrameRunIsEvaluatedFromItsAlignmentOn) {
  Trajectory est = read_dataset_groundtruth(micro_);
  const std::int64_t from = est.poses[est.poses.size() / 2].stamp_ns;
  for (auto& pose : est.poses) pose.T_XB.translation().x() += pose.stamp_ns < from ? 5.0 : 0.1;  // L, then W
  write_tum(dir_ / "run" / "trajectory.tum", est);
  std::ofstream(dir_ / "run" / "run.json")
      << "{\"aligned_from_stamp_ns\": " << from << ", \"aligned_after_s\": 2.5}\n";
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "run").string() + " --json");
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_NEAR(j["ate_pos_rmse_m"].get<double>(), 0.1, 1e-9);
  EXPECT_EQ(j["evaluated_from_stamp_ns"], from);
  const Outcome table = run("--gt " + micro_ + " --est " + (dir_ / "run").string());
  EXPECT_NE(table.out.find("evaluated from the run's alignment to W on, 2.5 s"), std::string::npos) << table.out;
  std::ofstream(dir_ / "run" / "run.json") << "{\"aligned_from_stamp_ns\": ";
  const Outcome broken = run("--gt " + micro_ + " --est " + (dir_ / "run").string());
  EXPECT_EQ(broken.code, 2);
  EXPECT_NE(broken.err.find("run.json: not a run.json"), std::string::npos) << broken.err;
}

// An estimator restarted mid-flight is back in its own L until it aligns again: run.json out_of_world_ns lists that
// stretch and eval leaves it out (here its poses are 50 m off), saying so.
TEST_F(EvalCli, StretchesOutOfWAfterTheAlignmentAreLeftOut) {
  Trajectory est = read_dataset_groundtruth(micro_);
  const std::size_t n = est.poses.size();
  const std::int64_t from = est.poses[n / 4].stamp_ns, gap0 = est.poses[n / 2].stamp_ns,
                     gap1 = est.poses[n / 2 + n / 8].stamp_ns;
  for (auto& pose : est.poses) {
    const bool out_of_w = pose.stamp_ns < from || (pose.stamp_ns >= gap0 && pose.stamp_ns <= gap1);
    pose.T_XB.translation().x() += out_of_w ? 50.0 : 0.1;
  }
  write_tum(dir_ / "run" / "trajectory.tum", est);
  std::ofstream(dir_ / "run" / "run.json") << "{\"aligned_from_stamp_ns\": " << from
                                           << ", \"aligned_after_s\": 1.0, \"out_of_world_ns\": [[" << gap0 << ", "
                                           << gap1 << "]]}\n";
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "run").string() + " --json");
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_NEAR(j["ate_pos_rmse_m"].get<double>(), 0.1, 1e-9);
  EXPECT_EQ(j["excluded_out_of_world_ns"][0][0], gap0);
  const Outcome table = run("--gt " + micro_ + " --est " + (dir_ / "run").string());
  EXPECT_NE(table.out.find("not evaluated: poses " + std::to_string(gap0)), std::string::npos) << table.out;
}

TEST_F(EvalCli, BadAlignmentAndMissingInputExitTwo) {
  EXPECT_EQ(run("--gt " + micro_ + " --est " + (dir_ / "run").string() + " --align se2").code, 2);
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "nothing").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("nothing"), std::string::npos) << o.err;
}

TEST_F(EvalCli, PlotsAreWritten) {
  const fs::path plots = dir_ / "plots";
  const Outcome o = run("--gt " + micro_ + " --est " + (dir_ / "run").string() + " --align posyaw --json --plots " +
                        plots.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_TRUE(nlohmann::json::parse(o.out).is_object());  // plots do not leak into the JSON
  for (const char* name : {"trajectory_xy.png", "trajectory_xz.png", "error_position.png", "error_rotation.png",
                           "rpe_translation.png", "rpe_rotation.png"}) {
    EXPECT_TRUE(fs::is_regular_file(plots / name)) << name;
    EXPECT_GT(fs::file_size(plots / name), 5000u) << name;
  }
}

}  // namespace
}  // namespace twinslam
