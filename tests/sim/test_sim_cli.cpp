// `twinslam sim` end to end on a short `tiny` flight: the dataset has the CONTRACTS.md layout, ingest loads it,
// the same seed gives identical CSV files and image pixels, and a different seed gives a different flight.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "scratch_dir.hpp"
#include "subprocess.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/features.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {
std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path simulate(const std::string& tag, const std::string& seed) {
  const fs::path out = fs::temp_directory_path() / ("twinslam_sim_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--duration", "10", "--seed",
                                    seed, "--features", "--quiet", "--out", out.string()},
                                   {}, std::chrono::seconds(240));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out;
}
}  // namespace

TEST(SimCli, TinyIsDeterministicAndReplayable) {
  const fs::path a = simulate("a", "11"), b = simulate("b", "11"), c = simulate("c", "12");
  for (const char* f : {"mav0/imu0/data.csv", "mav0/gnss0/data.csv", "mav0/cam0/data.csv", "mav0/cam0/features.csv",
                        "mav0/state_groundtruth_estimate0/data.csv", "groundtruth.tum", "mav0/cam0/sensor.yaml",
                        "mav0/imu0/sensor.yaml", "dataset.yaml", "twin/twin.ply"}) {
    ASSERT_TRUE(fs::exists(a / f)) << f;
    EXPECT_EQ(slurp(a / f), slurp(b / f)) << f << " differs between two runs with the same seed";
  }
  EXPECT_NE(slurp(a / "mav0/imu0/data.csv"), slurp(c / "mav0/imu0/data.csv"));

  const auto ds = ingest::load_dataset(a);  // what ingest will replay
  EXPECT_EQ(ds.images.size(), 201u);        // 10 s at 20 Hz, both ends included
  EXPECT_EQ(ds.imu.size(), 2001u);
  EXPECT_EQ(ds.gnss.size(), 51u);
  for (std::size_t k = 0; k < ds.images.size(); k += 40) {
    const cv::Mat ia = cv::imread(ds.images[k].file.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat ib = cv::imread((b / "mav0/cam0/data" / ds.images[k].file.filename()).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(ia.size(), cv::Size(640, 400));
    EXPECT_EQ(cv::countNonZero(ia != ib), 0) << "frame " << k << " differs";
  }
  const auto tracks = ingest::load_feature_tracks(a / "mav0/cam0/features.csv");
  EXPECT_EQ(tracks.size(), ds.images.size());
  std::size_t total = 0;
  for (const auto& f : tracks) total += f.features.size();
  EXPECT_GT(total / tracks.size(), 100u) << "too few ideal features per frame";
  for (const auto& d : {a, b, c}) fs::remove_all(d);
}

TEST(SimCli, BadScenarioKeyIsExitTwoNamingTheKey) {
  const fs::path f = test::scratch_dir() / "bad_scenario.yaml";
  std::ofstream(f) << "seed: 3\nimu: {rate_hz: -5}\n";
  const auto r = test::run_process({test::bin("twinslam"), "sim", "--scenario", f.string(), "--out", "/tmp/never"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("imu.rate_hz"), std::string::npos) << r.err;
  std::ofstream(f) << "seed: 3\nbogus_key: 1\n";
  const auto u = test::run_process({test::bin("twinslam"), "sim", "--scenario", f.string(), "--out", "/tmp/never"});
  EXPECT_EQ(u.exit_code, 2);
  EXPECT_NE(u.err.find("bogus_key"), std::string::npos) << u.err;
}
