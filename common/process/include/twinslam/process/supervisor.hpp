#pragma once
// Starts service processes and watches them: the engine of `twinslam launch` and `twinslam run`. Pure POSIX, no DDS.
// Each child runs in its own process group, so a Ctrl-C in the terminal reaches only the supervisor, which then
// sends exactly one SIGINT to each child (a second signal would make a child skip its clean shutdown).
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace twinslam::process {

struct ProcessSpec {
  std::string name;                          // shown as the log prefix
  std::string exec;                          // a path, or a name looked up next to the running binary, then in PATH
  std::vector<std::string> args;
  std::map<std::string, std::string> env;    // added to (or overriding) the supervisor's environment
  std::filesystem::path cwd;                 // empty: inherit
  bool required = false;                     // its exit (any code) ends the whole group
  // Restart after a failure (non-zero exit or a signal), with back-off: restart_delay_s, doubled per restart of the
  // same service up to 16x, at most max_restarts times; then its failure ends the group as without the policy.
  bool restart_on_failure = false;
  int max_restarts = 5;
  double restart_delay_s = 0.5;              // [s]
};

// One restart made under ProcessSpec::restart_on_failure.
struct RestartEvent {
  std::string name;
  double at_s = 0.0;                         // when the new process started, since the supervisor was made [s]
  int attempt = 0;                           // 1 for the first restart of this service
  std::optional<int> exit_code, signal;      // how the previous process ended
  int old_pid = 0, new_pid = 0;
};

struct ChildResult {
  std::string name;
  int pid = 0;
  std::optional<int> exit_code;              // set once exited normally
  std::optional<int> signal;                 // set if killed by a signal
  bool ok() const { return exit_code && *exit_code == 0; }
};

// Where a child's output goes: prefixed onto our stdout/stderr ("name | line"), or into <dir>/<name>.log.
struct OutputPolicy {
  std::filesystem::path log_dir;             // empty: prefix onto the console
};

class Supervisor {
 public:
  explicit Supervisor(OutputPolicy output = {});
  ~Supervisor();  // stops whatever still runs
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // Throws UsageError if the executable cannot be found; std::runtime_error if fork/exec fails.
  void start(const ProcessSpec& spec);

  // Why watch() returned.
  enum class Event { Shutdown, ChildFailed, RequiredExited, AllExited, Timeout };
  // Blocks until a stop is requested (signal), a child exits non-zero, a required child exits, all exited, or timeout.
  Event watch(std::chrono::milliseconds timeout = std::chrono::hours(24 * 365));

  // Has the named child exited? (non-blocking)
  std::optional<ChildResult> exited(const std::string& name);

  // SIGINT to every running child, SIGKILL to those still running after `grace`. Returns all results.
  std::vector<ChildResult> stop_all(std::chrono::milliseconds grace = std::chrono::milliseconds(5000));

  // One result per service: its latest process.
  std::vector<ChildResult> results() const;
  // Every restart made so far, in order.
  std::vector<RestartEvent> restarts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// How a process ended, for people: "exit code N" or "signal N".
std::string describe_end(const std::optional<int>& exit_code, const std::optional<int>& signal);

// Finds `exec` as Supervisor::start would; empty if not found.
std::filesystem::path resolve_executable(const std::string& exec);

}  // namespace twinslam::process
