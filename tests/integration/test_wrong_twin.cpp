// Issue 15 item 4: a wrong twin. Each scenario of deploy/scenarios/wrong-twin-*.yaml (tiny with one building shifted
// 3 m, one removed, one added; a city of identical blocks) is simulated with ideal tracks and benchmarked in
// vio-gnss and vio-twin. What a user relies on: no accepted registration took a wrong surface for the truth (one
// locked to the shifted facades would be ~3 m off, one slid along the aliased street a block pitch, 60 m), and
// fusing the wrong twin never made the estimate worse than GNSS alone.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "text_file.hpp"

namespace fs = std::filesystem;
using namespace twinslam;
using twinslam::test::read_text;

namespace {

const fs::path kScenarios = TWINSLAM_SCENARIO_DIR;
const fs::path kWork = TWINSLAM_WRONG_TWIN_WORK_DIR;

// The bound on an accepted registration's position error [m]. The twin's own 0.2 m per-surface noise and the VIO
// cloud's depth errors give up to 0.81 m on the unchanged twin of the same flight (tiny, 50 s: 6 of 53 accepted
// registrations beyond 0.5 m; up to 1.31 m on city-long, README "Registration against the twin"); one fitted
// to a wrong surface is off by about the change itself (3 m; 2.55 m measured when tiny's 30 s loop met the removed
// building during acquisition; a block pitch, 60 m, in the aliased street).
constexpr double kMaxRegistrationError_m = 1.5;


// `twinslam sim --scenario deploy/scenarios/NAME.yaml --features`, then `twinslam bench --modes vio-gnss,vio-twin`;
// returns BENCH/metrics.json (null on failure, with the output in *log).
nlohmann::json bench(const std::string& name, std::string* log) {
  const fs::path base = kWork / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const fs::path exe = test::bin("twinslam");
  const auto sim = test::run_process({exe, "sim", "--scenario", (kScenarios / (name + ".yaml")).string(), "--out",
                                      (base / "data").string(), "--features", "--quiet"},
                                     {}, std::chrono::seconds(240));
  *log = sim.out + sim.err;
  if (sim.exit_code != 0) return nullptr;
  const auto run = test::run_process({exe, "bench", (base / "data").string(), "--out", (base / "bench").string(),
                                      "--features", "--modes", "vio-gnss,vio-twin"},
                                     {{"TWINSLAM_CACHE", (base / "cache").string()}}, std::chrono::seconds(480));
  *log += run.out + run.err;
  // bench ends 1 when a mode never declared its world alignment (vio-gnss on tiny's loops); its metrics.json holds
  // the modes that did.
  if (!fs::exists(base / "bench/metrics.json")) return nullptr;
  auto metrics = nlohmann::json::parse(read_text(base / "bench/metrics.json"));
  fs::remove_all(base);
  return metrics;
}

void expect_wrong_twin_is_harmless(const std::string& name) {
  std::string log;
  const nlohmann::json m = bench(name, &log);
  ASSERT_FALSE(m.is_null()) << log;
  ASSERT_TRUE(m.contains("vio-twin")) << "vio-twin declared its world alignment: " << m.dump();
  const nlohmann::json& truth = m["vio-twin"]["registrations_vs_truth"];
  ASSERT_GT(truth.value("accepted", 0), 10) << "the twin is used: " << m.dump();
  EXPECT_LE(truth["max_after_m"].get<double>(), kMaxRegistrationError_m) << truth.dump();
  const double twin = m["vio-twin"]["ate_pos_rmse_m"];
  // vio-gnss is in metrics.json only if it declared its world alignment (on tiny's loops its GNSS heading fit is not
  // 3 deg certain within 50 s): a baseline without a world frame has nothing vio-twin could be worse than.
  const double gnss = m.contains("vio-gnss") ? m["vio-gnss"]["ate_pos_rmse_m"].get<double>() : -1;
  if (gnss >= 0) {
    EXPECT_LE(twin, gnss);
  }
  std::printf("%s: ATE in W vio-twin %.3f m, vio-gnss %.3f m (-1: never in W); registrations %s\n", name.c_str(),
              twin, gnss, truth.dump().c_str());
}

}  // namespace

TEST(WrongTwin, ABuildingShiftedThreeMetresIsNeverTakenForTheTruth) {
  expect_wrong_twin_is_harmless("wrong-twin-shifted");
}

TEST(WrongTwin, ABuildingMissingFromTheTwinPullsNoRegistrationAway) {
  expect_wrong_twin_is_harmless("wrong-twin-removed");
}

TEST(WrongTwin, ABuildingOnlyTheTwinHasPullsNoRegistrationAway) {
  expect_wrong_twin_is_harmless("wrong-twin-added");
}

TEST(WrongTwin, AStreetOfIdenticalBlocksDoesNotAliasARegistration) {
  expect_wrong_twin_is_harmless("wrong-twin-aliased");
}
