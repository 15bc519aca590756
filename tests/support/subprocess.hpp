#pragma once
// Test support: run a program as a child process and collect its exit code and output, or keep it running in the
// background to signal it later. Used by the CLI and multi-process tests.
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include <sys/types.h>

namespace twinslam::test {

struct ProcessOutput {
  int exit_code = -1;  // -1: killed by a signal or timed out
  std::string out, err;
};

// Runs argv[0] (absolute path) with extra environment; kills it after `timeout`.
ProcessOutput run_process(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env = {},
                          std::chrono::seconds timeout = std::chrono::seconds(120));

class Background {
 public:
  Background(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env = {});
  ~Background();  // SIGKILL if still running
  pid_t pid() const { return pid_; }
  void signal(int sig) const;
  // Waits for exit; returns the exit code, or -1 on timeout/signal death.
  int wait(std::chrono::milliseconds timeout);
  std::string output() const;  // stdout+stderr so far (from a temp file)

 private:
  pid_t pid_ = -1;
  std::string log_;
  bool exited_ = false;
};

std::string bin(const std::string& name);  // path of a built executable
// A TCP port nobody listens on now on the loopback interface (the kernel's pick for port 0).
int free_tcp_port();
// A DDS domain for one test: distinct per test process so parallel ctest jobs never share a domain.
int test_domain();

}  // namespace twinslam::test
