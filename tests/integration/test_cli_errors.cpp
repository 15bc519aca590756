// Acceptance (issue 2): each bad input ends with exit code 2 and a one-line reason naming the file and the problem.
#include <filesystem>

#include <gtest/gtest.h>

#include "dataset_fixture.hpp"
#include "subprocess.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {
// Exit code 2 and exactly one line on stderr that contains every expected fragment.
void expect_bad_input(const test::ProcessOutput& r, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' not in: " << r.err;
}

test::ProcessOutput run_ingest(const fs::path& dataset) {
  return test::run_process({test::bin("twinslam-ingest"), "--dataset", dataset.string()},
                           {{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}});
}
}  // namespace

TEST(CliErrors, MissingDatasetFolder) {
  expect_bad_input(run_ingest("/nonexistent/ds"), {"/nonexistent/ds", "dataset folder does not exist"});
  expect_bad_input(test::run_process({test::bin("twinslam"), "run", "/nonexistent/ds", "--mode", "vio", "--out",
                                      "/tmp/twinslam_never"}),
                   {"/nonexistent/ds", "does not exist"});
}

TEST(CliErrors, MalformedCsvRowNamesFileAndLine) {
  const auto dir = test::broken_copy("cli_badrow", [](const fs::path& d) {
    test::replace_line(d / "mav0/imu0/data.csv", 10, "1403715273307142912,0.1,0.2");
  });
  expect_bad_input(run_ingest(dir), {(dir / "mav0/imu0/data.csv").string() + ":10:", "expected 7 columns, found 3"});
}

TEST(CliErrors, TimestampsGoingBackwards) {
  const auto dir = test::broken_copy("cli_backwards", [](const fs::path& d) {
    test::replace_line(d / "mav0/imu0/data.csv", 5, "1403715273000000000,0.1,0.2,0.3,9.0,0.1,0.2");
  });
  expect_bad_input(run_ingest(dir), {(dir / "mav0/imu0/data.csv").string() + ":5:", "is not after the previous one"});
}

TEST(CliErrors, MissingImageFile) {
  const auto dir = test::broken_copy("cli_noimage", [](const fs::path& d) {
    fs::remove(d / "mav0/cam0/data/1403715275262142976.png");
  });
  expect_bad_input(run_ingest(dir), {"1403715275262142976.png", "does not exist", "cam0/data.csv:"});
}

TEST(CliErrors, UnknownParticipantProfile) {
  const auto r = test::run_process({test::bin("twinslam-tiles"), "--profile", "no.such.profile"},
                                   {{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}});
  expect_bad_input(r, {"twinslam.xml", "no participant profile named 'no.such.profile'"});
}

TEST(CliErrors, MissingQosFile) {
  const auto r = test::run_process({test::bin("twinslam-tiles"), "--qos", "/nonexistent/qos.xml"});
  expect_bad_input(r, {"/nonexistent/qos.xml", "QoS profile file not found"});
}

TEST(CliErrors, MalformedLaunchFile) {
  const fs::path f = fs::temp_directory_path() / ("twinslam_bad_launch_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(f) << "services:\n  - name: a\n    exec: twinslam-tracking\n    argz: [1]\n";
  expect_bad_input(test::run_process({test::bin("twinslam"), "launch", f.string()}),
                   {f.string(), "unknown key 'services[0].argz'"});
  std::ofstream(f) << "services: [\n";
  expect_bad_input(test::run_process({test::bin("twinslam"), "launch", f.string()}), {f.string(), "invalid YAML"});
}

TEST(CliErrors, UnknownTopicForEcho) {
  expect_bad_input(test::run_process({test::bin("twinslam"), "echo", "nope"}), {"unknown topic 'nope'"});
}
