// Supervisor restarts (ProcessSpec::restart_on_failure): a crashed or killed service comes back with back-off and is
// recorded; one that keeps failing, or refuses its input (exit code 2), ends the group as without the policy.
#include <csignal>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "twinslam/process/supervisor.hpp"

namespace twinslam::process {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

ProcessSpec shell(const std::string& name, const std::string& script, bool restart, int max_restarts = 5) {
  ProcessSpec s;
  s.name = name;
  s.exec = "sh";
  s.args = {"-c", script};
  s.restart_on_failure = restart;
  s.max_restarts = max_restarts;
  s.restart_delay_s = 0.02;
  return s;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("twinslam_supervisor_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Supervisor, AServiceThatCrashesOnceIsRestartedAndTheRestartRecorded) {
  const fs::path dir = fresh_dir("once");
  Supervisor sup({dir / "logs"});
  // Fails the first time (leaving a marker and a line in its log), succeeds the second.
  ProcessSpec s = shell("edge", "if [ -e " + (dir / "m").string() + " ]; then echo second; exit 0; fi; touch " +
                                    (dir / "m").string() + "; echo first; exit 3", true);
  s.required = true;
  sup.start(s);
  EXPECT_EQ(sup.watch(10s), Supervisor::Event::RequiredExited);
  const auto restarts = sup.restarts();
  ASSERT_EQ(restarts.size(), 1u);
  EXPECT_EQ(restarts[0].name, "edge");
  EXPECT_EQ(restarts[0].attempt, 1);
  EXPECT_EQ(restarts[0].exit_code, 3);
  EXPECT_NE(restarts[0].old_pid, restarts[0].new_pid);
  const auto results = sup.results();
  ASSERT_EQ(results.size(), 1u);  // the latest process of the service
  EXPECT_TRUE(results[0].ok());
  sup.stop_all();
  fs::remove_all(dir);
}

TEST(Supervisor, AKilledServiceComesBackWhileTheOthersRunOn) {
  Supervisor sup;
  sup.start(shell("registration", "sleep 30", true));
  sup.start(shell("estimator", "sleep 30", false));
  EXPECT_EQ(sup.watch(100ms), Supervisor::Event::Timeout);
  const int first_pid = sup.results()[0].pid;
  ASSERT_EQ(::kill(first_pid, SIGKILL), 0);
  EXPECT_EQ(sup.watch(500ms), Supervisor::Event::Timeout);  // not ChildFailed: it was restarted
  const auto restarts = sup.restarts();
  ASSERT_EQ(restarts.size(), 1u);
  EXPECT_EQ(restarts[0].signal, SIGKILL);
  EXPECT_EQ(restarts[0].old_pid, first_pid);
  EXPECT_FALSE(sup.exited("registration"));  // the new process runs
  EXPECT_FALSE(sup.exited("estimator"));
  sup.stop_all(1000ms);
}

TEST(Supervisor, AServiceThatKeepsFailingGivesUpAfterMaxRestarts) {
  Supervisor sup;
  sup.start(shell("flaky", "exit 4", true, 2));
  EXPECT_EQ(sup.watch(10s), Supervisor::Event::ChildFailed);
  EXPECT_EQ(sup.restarts().size(), 2u);
  EXPECT_EQ(sup.restarts()[1].attempt, 2);
}

TEST(Supervisor, BadInputAndServicesWithoutThePolicyAreNotRestarted) {
  Supervisor refused;
  refused.start(shell("tiles", "exit 2", true));  // exit code 2: the service refused its input
  EXPECT_EQ(refused.watch(10s), Supervisor::Event::ChildFailed);
  EXPECT_TRUE(refused.restarts().empty());
  Supervisor plain;
  plain.start(shell("estimator", "exit 1", false));
  EXPECT_EQ(plain.watch(10s), Supervisor::Event::ChildFailed);
  EXPECT_TRUE(plain.restarts().empty());
}

}  // namespace
}  // namespace twinslam::process
