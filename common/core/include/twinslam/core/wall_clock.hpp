#pragma once
// The wall clock as the messages that carry it use it: nanoseconds since the Unix epoch. For display and for the
// receive times of recordings and the Foxglove bridge; never compared across hosts.
#include <chrono>
#include <cstdint>

namespace twinslam {

inline std::uint64_t unix_time_ns() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count());
}

}  // namespace twinslam
