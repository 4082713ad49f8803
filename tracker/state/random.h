// Random numbers for the particle filter: one small generator per particle and step,
// seeded from (seed, frame, layer, particle), so a particle's draws do not depend on which
// thread evaluates it or in which order: results are identical for any thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace jgpm {

class Random {
 public:
  // SplitMix64 of the key's parts: any change in any part gives an unrelated stream.
  Random(uint64_t seed, uint64_t a = 0, uint64_t b = 0, uint64_t c = 0)
      : state_(Mix(Mix(Mix(Mix(seed) ^ a) ^ (b * 0x9e3779b97f4a7c15ULL)) ^ (c * 0xbf58476d1ce4e5b9ULL))) {}

  uint64_t Next() {  // SplitMix64
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    return Mix(z);
  }
  // Uniform in [0, 1).
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  // Standard normal (Box-Muller; the second value is kept for the next call).
  double Normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = Uniform();
    while (u <= 0) u = Uniform();
    const double r = std::sqrt(-2 * std::log(u)), angle = 2 * std::numbers::pi * Uniform();
    spare_ = r * std::sin(angle);
    has_spare_ = true;
    return r * std::cos(angle);
  }

 private:
  static uint64_t Mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  uint64_t state_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace jgpm
