// Errors by height band, and `twinslam gnss errors` on a simulated flight (ray-traced GNSS against its ground truth).
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "twinslam/gnss/height_bands.hpp"

namespace twinslam::gnss {
namespace {

TEST(GnssHeightBands, SamplesFallIntoTheirBandsWithTheirStatistics) {
  std::vector<HeightSample> s;
  for (int i = 1; i <= 10; ++i) s.push_back({2.0, static_cast<double>(i), 1.0});  // 0-5: errors 1..10
  s.push_back({-0.5, 100.0, 2.0});   // below the first edge: counted in the first band
  s.push_back({7.0, 3.0, 4.0});      // 5-10
  s.push_back({35.0, 0.5, 0.25});    // > 20
  const auto b = errors_by_height(s);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[0].name, "0-5");
  EXPECT_EQ(b[3].name, "> 20");
  EXPECT_EQ(b[0].fixes, 11u);
  EXPECT_DOUBLE_EQ(b[0].h_median_m, 6.0);
  EXPECT_NEAR(b[0].h_mean_m, 155.0 / 11, 1e-12);
  EXPECT_EQ(b[1].fixes, 1u);
  EXPECT_DOUBLE_EQ(b[1].v_median_m, 4.0);
  EXPECT_EQ(b[2].fixes, 0u);
  EXPECT_EQ(b[3].fixes, 1u);
  EXPECT_DOUBLE_EQ(b[3].h_p95_m, 0.5);
}

TEST(GnssHeightBands, ErrorsCommandReadsASimulatedFlight) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("twinslam_gnss_errors_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string twinslam = std::string(TWINSLAM_BIN_DIR) + "/twinslam";
  const auto sim = test::run_process({twinslam, "sim", "--scenario", "tiny", "--out", dir.string(), "--no-images"});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  ASSERT_TRUE(fs::exists(dir / "mav0/gnss0/pseudoranges.csv"));
  const auto r = test::run_process({twinslam, "gnss", "errors", dir.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["fixes"].get<int>(), 100);  // 30 s at 5 Hz, most epochs with a fix
  std::size_t in_bands = 0;
  for (const auto& b : j["bands"]) {
    in_bands += b["fixes"].get<std::size_t>();
    if (b["fixes"].get<int>() == 0) continue;
    EXPECT_GT(b["h_median_m"].get<double>(), 0.05);  // a real error model, not the truth
    EXPECT_LT(b["h_median_m"].get<double>(), 30.0);
  }
  EXPECT_EQ(in_bands, j["fixes"].get<std::size_t>());
  EXPECT_GT(j["signals"]["signals"].get<int>(), 4 * j["signals"]["epochs"].get<int>());
  const auto bad = test::run_process({twinslam, "gnss", "errors", (dir / "nothing").string()});
  EXPECT_EQ(bad.exit_code, 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace twinslam::gnss
