// The built-in web view during a real tiny run (issue 16 item 2): `twinslam run --bridge PORT` serves the page on the
// bridge's port, `twinslam view` finds it, and Debian's chromium (driven by playwright-core from npm,
// tests/node/web_view.test.mjs, a test of node's runner) opens it: the twin's tiles are drawn and the trajectory
// grows between two screenshots (checked on their pixels).
#include <unistd.h>

#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {

const fs::path& base() {
  static const fs::path dir = fs::temp_directory_path() / ("twinslam_web_view_" + std::to_string(::getpid()));
  return dir;
}

TEST(WebView, ChromiumSeesTheTilesAndAGrowingTrajectoryDuringATinyRun) {
  fs::remove_all(base());
  // 60 s of flight rather than tiny's 30: on a loaded machine chromium and SwiftShader once took longer than the
  // whole 30 s run to show the first frame, and nothing grew after it.
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--duration", "60", "--out",
                                      (base() / "tiny").string(), "--features", "--quiet"},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  const std::string port = std::to_string(test::free_tcp_port());
  // Nothing listens yet: `twinslam view` says so in one line (exit 2), no browser is started.
  const auto none = test::run_process({test::bin("twinslam"), "view", "--no-open", "--port", port});
  EXPECT_EQ(none.exit_code, 2) << none.out << none.err;
  EXPECT_NE(none.err.find("no bridge answers at 127.0.0.1:" + port), std::string::npos) << none.err;
  // The browser test first: it retries until the bridge serves the page. Real time, so the run lasts ~60 s on screen.
  test::Background browser({TWINSLAM_NODE, std::string(TWINSLAM_SOURCE_DIR) + "/tests/node/web_view.test.mjs"},
                           {{"TWINSLAM_VIEW_URL", "http://127.0.0.1:" + port + "/"},
                            {"TWINSLAM_VIEW_SHOTS", (base() / "shots").string()},
                            {"TWINSLAM_VIEW_WAIT_S", "120"}});
  test::Background run({test::bin("twinslam"), "run", (base() / "tiny").string(), "--mode", "vio-twin", "--features",
                        "--realtime", "--no-progress", "--bridge", port, "--out", (base() / "run").string(),
                        "--domain", std::to_string(test::test_domain())});
  // `twinslam view` against the live bridge: the page is there, its URL printed (no display here: not opened).
  test::ProcessOutput view;
  for (int i = 0; i < 120; ++i) {
    view = test::run_process({test::bin("twinslam"), "view", "--no-open", "--port", port});
    if (view.exit_code == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  EXPECT_EQ(view.exit_code, 0) << view.out << view.err;
  EXPECT_NE(view.out.find("web view: http://127.0.0.1:" + port + "/"), std::string::npos) << view.out;
  EXPECT_EQ(browser.wait(std::chrono::seconds(360)), 0) << browser.output();
  EXPECT_EQ(run.wait(std::chrono::seconds(240)), 0) << run.output();
  EXPECT_TRUE(fs::is_regular_file(base() / "shots" / "view-1.png"));
  EXPECT_TRUE(fs::is_regular_file(base() / "shots" / "view-2.png"));
  fs::remove_all(base());
}

}  // namespace
