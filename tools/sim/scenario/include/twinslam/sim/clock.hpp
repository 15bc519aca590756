#pragma once
// Simulated sensor time. Files carry integer nanoseconds from a fixed epoch so that stamps look like real ones (about
// 1e18 ns) and all streams (IMU, camera, GNSS, ground truth) share one clock: sample k of a stream at rate r [Hz] is
// taken at t = round(k * 1e9 / r) ns after the epoch, and every model is evaluated at exactly that time.
#include <cmath>
#include <cstdint>
#include <vector>

namespace twinslam::sim {

inline constexpr std::int64_t kEpochNs = 1'000'000'000'000'000'000;  // stamp of simulation time t = 0

// Stamp [ns] of simulation time t [s].
inline std::int64_t stamp_ns(double t_s) { return kEpochNs + std::llround(t_s * 1e9); }

// Simulation time [s] of a stamp.
inline double time_s(std::int64_t stamp) { return static_cast<double>(stamp - kEpochNs) * 1e-9; }

// Stamps of a stream at rate_hz [Hz] covering [0, duration_s] (both ends included when they fall on a sample).
inline std::vector<std::int64_t> sample_stamps(double rate_hz, double duration_s) {
  std::vector<std::int64_t> out;
  const double period_ns = 1e9 / rate_hz;
  const auto end_ns = std::llround(duration_s * 1e9);
  for (std::int64_t k = 0;; ++k) {
    const auto offset = std::llround(static_cast<double>(k) * period_ns);
    if (offset > end_ns) break;
    out.push_back(kEpochNs + offset);
  }
  return out;
}

}  // namespace twinslam::sim
