#pragma once
// Seeded randomness for the world generator, twin and renderer. Our own uniform/normal maps on top of the raw
// std::mt19937_64 stream (whose output the C++ standard fixes) because the std distributions may differ between
// standard libraries: the same seed must give the same city everywhere.
#include <cmath>
#include <cstdint>
#include <random>

namespace twinslam::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int integer(int n) { return static_cast<int>(uniform() * n); }                  // [0, n)
  bool chance(double p) { return uniform() < p; }
  double normal() {  // Box-Muller, one value per call
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 engine_;
};

// Stateless 64-bit mix (SplitMix64 finalizer): per-pixel and per-texture-cell randomness that does not depend on
// the order of evaluation, so multi-threaded rendering stays bit-identical.
inline std::uint64_t hash64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace twinslam::sim
