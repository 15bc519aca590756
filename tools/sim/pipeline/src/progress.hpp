#pragma once
// A one-line progress bar with ETA on stderr (redrawn in place on a terminal, every 10 % otherwise).
#include <chrono>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace twinslam::sim {

class Progress {
 public:
  Progress(std::string what, std::size_t total, bool enabled)
      : what_(std::move(what)), total_(total), enabled_(enabled), tty_(isatty(STDERR_FILENO) != 0),
        start_(std::chrono::steady_clock::now()) {}

  void update(std::size_t done) {
    if (!enabled_ || total_ == 0) return;
    const int percent = static_cast<int>(100 * done / total_);
    if (!tty_ && percent / 10 == last_percent_ / 10 && done != total_) return;
    if (percent == last_percent_ && done != total_) return;
    last_percent_ = percent;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = done == 0 ? 0.0 : elapsed * (total_ - done) / done;
    const int width = 30, filled = width * percent / 100;
    std::fprintf(stderr, "%s%-10s [%s%s] %3d%% %zu/%zu  %.0fs elapsed, ETA %.0fs%s", tty_ ? "\r" : "", what_.c_str(),
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), percent, done, total_,
                 elapsed, eta, tty_ ? "" : "\n");
    if (tty_ && done == total_) std::fprintf(stderr, "\n");
  }

 private:
  std::string what_;
  std::size_t total_;
  bool enabled_, tty_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace twinslam::sim
