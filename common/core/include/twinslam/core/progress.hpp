#pragma once
// Progress of a long command (sim, run, bench, twin build): a one-line bar with ETA redrawn in place on a terminal,
// or plain lines (every 10 % and at the end) when the stream is not a terminal (CI logs, pipes, tests).
#include <chrono>
#include <cstdio>
#include <string>

namespace twinslam {

class Progress {
 public:
  // what: a short label ("rendering", "run vio-twin"); total: units of work (0: nothing is printed);
  // enabled false: silent. `out` defaults to stderr, so stdout keeps only the command's results.
  Progress(std::string what, std::size_t total, bool enabled, std::FILE* out = stderr);
  // Forces the plain-line style whatever `out` is (tests, callers that know the stream is a log).
  void set_plain() { tty_ = false; }

  // `done` of total so far (clamped to total); prints when the shown percentage changes (terminal) or passes a
  // 10 % step (plain). Not thread-safe: call from one thread.
  void update(std::size_t done);
  // Ends the bar at `done` with a last line even if the work stopped short (an interrupted run shows where).
  void finish(std::size_t done);

 private:
  void print(std::size_t done, int percent);

  std::string what_;
  std::size_t total_;
  bool enabled_, tty_;
  std::FILE* out_;
  int last_percent_ = -10;  // below any step, so the first update prints (-1 / 10 would be step 0)
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace twinslam
