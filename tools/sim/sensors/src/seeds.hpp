#pragma once
// One independent random stream per sensor from the scenario seed, so that adding a sensor does not change the others.
#include <cstdint>
#include <random>

namespace twinslam::sim::detail {

enum class Stream : std::uint32_t {
  Imu = 1, Gnss = 2, Route = 3, GnssRaytrace = 4,  // 4: pipeline/gnss_raytrace.cpp
  ImuDevice = 11, ImuInstability = 12, CameraExtrinsics = 13, CameraIntrinsics = 14  // imperfect sensors (issue 13)
};

inline std::mt19937_64 make_rng(std::uint64_t seed, Stream stream) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(stream)};
  return std::mt19937_64(seq);
}

}  // namespace twinslam::sim::detail
