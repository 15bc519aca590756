#include "twinslam/core/progress.hpp"

#include <algorithm>

#include <unistd.h>

namespace twinslam {

Progress::Progress(std::string what, std::size_t total, bool enabled, std::FILE* out)
    : what_(std::move(what)), total_(total), enabled_(enabled && total > 0), tty_(isatty(fileno(out)) != 0),
      out_(out), start_(std::chrono::steady_clock::now()) {}

void Progress::update(std::size_t done) {
  if (!enabled_ || finished_) return;
  done = std::min(done, total_);
  const int percent = static_cast<int>(100 * done / total_);
  if (done == total_) {
    finish(done);
    return;
  }
  // Plain lines only at each 10 % step, so a log of a long run stays short.
  if (!tty_ && percent / 10 == last_percent_ / 10) return;
  if (percent == last_percent_) return;
  last_percent_ = percent;
  print(done, percent);
}

void Progress::finish(std::size_t done) {
  if (!enabled_ || finished_) return;
  finished_ = true;
  done = std::min(done, total_);
  print(done, static_cast<int>(100 * done / total_));
  if (tty_) std::fputc('\n', out_);
  std::fflush(out_);
}

void Progress::print(std::size_t done, int percent) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = done == 0 ? 0.0 : elapsed * static_cast<double>(total_ - done) / static_cast<double>(done);
  const int width = 30, filled = width * percent / 100;
  std::fprintf(out_, "%s%-10s [%s%s] %3d%% %zu/%zu  %.0fs elapsed, ETA %.0fs%s", tty_ ? "\r" : "", what_.c_str(),
               std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), percent, done, total_,
               elapsed, eta, tty_ ? "" : "\n");
  std::fflush(out_);
}

}  // namespace twinslam
