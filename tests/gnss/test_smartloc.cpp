// The smartLoc reader on the real Berlin excerpt and on broken files, and `twinslam gnss solve` end to end.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "scratch_dir.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/gnss/smartloc.hpp"

namespace twinslam::gnss {
namespace {

namespace fs = std::filesystem;
const std::string kDir = std::string(TWINSLAM_SHARED_DIR) + "/data/gnss/smartloc-berlin-potsdamer-platz-90s/";
const std::string kInput = kDir + "Berlin_Potsdamer_Platz_Input_first90s.txt";
const std::string kTruth = kDir + "Berlin_Potsdamer_Platz_GT_first90s.txt";

std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p = twinslam::test::scratch_dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(GnssSmartLoc, ReadsTheBerlinExcerpt) {
  const std::vector<Epoch> epochs = read_smartloc_pseudoranges(kInput);
  std::size_t n = 0;
  for (const Epoch& e : epochs) n += e.observations.size();
  EXPECT_EQ(n, 6393u);  // every pseudorange3 line of the file
  EXPECT_EQ(epochs.size(), 432u);
  const Pseudorange& p = epochs[0].observations[0];  // "pseudorange3 0 19949087.65382 25 14567933.924248 ..."
  EXPECT_DOUBLE_EQ(p.range_m, 19949087.65382);
  EXPECT_DOUBLE_EQ(p.sigma_m, 5.0);
  EXPECT_EQ(p.satellite_id, 12);
  EXPECT_EQ(p.system, SatSystem::kGps);
  EXPECT_EQ(epochs[0].observations[1].system, SatSystem::kGlonass);
  EXPECT_EQ(read_smartloc_ground_truth(kTruth).size(), 432u);
}

TEST(GnssSmartLoc, BrokenFilesNameTheFileLineAndProblem) {
  const std::string good = "pseudorange3 0 2e7 25 1 2 3 12 1 45 40\n";
  auto err = [&](const std::string& text) {
    const std::string p = write_temp("bad.txt", text);
    return error_of([&] { read_smartloc_pseudoranges(p); });
  };
  EXPECT_NE(err(good + "pseudorange3 0 2e7 25 1 2 3 12 1 45\n").find("bad.txt:2: pseudorange3: expected 10 numbers"),
            std::string::npos);
  EXPECT_NE(err(good + "pseudorange3 0 nan 25 1 2 3 12 1 45 40\n").find(":2: pseudorange3 value 2: 'nan'"),
            std::string::npos);
  EXPECT_NE(err(good + "pseudorange3 0 2e7 0 1 2 3 12 1 45 40\n").find(":2: pseudorange3: variance must be > 0"),
            std::string::npos);
  EXPECT_NE(err("pseudorange3 1 2e7 25 1 2 3 12 1 45 40\n" + good).find(":2: pseudorange3: time goes backwards"),
            std::string::npos);
  EXPECT_NE(err(good + "velocity3 0 1 2 3\n").find(":2: unknown line kind 'velocity3'"), std::string::npos);
  EXPECT_NE(err("pseudorange3 0 2e7 25 1 2 3 12 3 45 40\n").find("unknown satellite system 3"), std::string::npos);
  EXPECT_NE(err("odom3 0 1 2 3 4 5 6 7 8 9 10 11 12\n").find("no pseudorange3 lines"), std::string::npos);
  EXPECT_NE(error_of([] { read_smartloc_pseudoranges("/nonexistent/in.txt"); }).find("cannot open file"),
            std::string::npos);
}

TEST(GnssSmartLoc, SolveCommandPrintsTheContractJsonAndWritesFixes) {
  const std::string out = (twinslam::test::scratch_dir() / "fixes.csv").string();
  const auto r = test::run_process(
      {std::string(TWINSLAM_BIN_DIR) + "/twinslam", "gnss", "solve", kInput, "--gt", kTruth, "--out", out, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["epochs"], 432);
  EXPECT_GE(j["fixes"].get<int>(), 400);
  // Urban canyon among high-rises: tens of metres, not kilometres (a broken receiver) and not centimetres (cheating).
  EXPECT_GT(j["h_err_median_m"].get<double>(), 2.0);
  EXPECT_LT(j["h_err_median_m"].get<double>(), 40.0);
  EXPECT_GE(j["h_err_p95_m"].get<double>(), j["h_err_median_m"].get<double>());
  EXPECT_TRUE(j.contains("h_err_rmse_m"));
  EXPECT_TRUE(j.contains("v_err_median_m"));
  std::ifstream in(out);
  std::string header, row;
  std::getline(in, header);
  std::size_t rows = 0;
  while (std::getline(in, row)) ++rows;
  EXPECT_EQ(rows, j["fixes"].get<std::size_t>());
  const auto bad = test::run_process({std::string(TWINSLAM_BIN_DIR) + "/twinslam", "gnss", "solve",
                                      "/nonexistent/in.txt", "--gt", kTruth});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("/nonexistent/in.txt: cannot open file"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace twinslam::gnss
