#pragma once
// Polls `pred` until it holds or `timeout` passes: for tests that wait on messages from DDS threads.
#include <chrono>
#include <thread>

namespace twinslam::testing {

template <class Pred>
bool wait_for(Pred pred, std::chrono::milliseconds timeout,
              std::chrono::milliseconds poll = std::chrono::milliseconds(1)) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(poll);
  }
  return true;
}

}  // namespace twinslam::testing
