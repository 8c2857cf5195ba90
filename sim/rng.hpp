#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>

namespace rotord::sim {

/// Small seeded generator (xorshift64*, seeded through splitmix64) with a
/// Box-Muller normal. Hand-written rather than std::normal_distribution because
/// the standard leaves that algorithm to the library: the same seed must give
/// the same trace with libstdc++, libc++ and the arm-none-eabi toolchain.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(splitmix64(seed)) {
    if (state_ == 0) state_ = 0x9E3779B97F4A7C15ull;  // xorshift must not start at 0
  }

  std::uint64_t next_u64() {
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return state_ * 0x2545F4914F6CDD1Dull;
  }

  /// Uniform in (0, 1]: never 0, so log() below is always finite.
  double uniform() {
    return (static_cast<double>(next_u64() >> 11) + 1.0) * (1.0 / 9007199254740992.0);
  }

  /// N(0, sigma). Uses one Box-Muller pair per call: simpler than caching the
  /// second value, and speed does not matter at 1 kHz.
  double normal(double sigma) {
    if (sigma <= 0.0) return 0.0;
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    return sigma * r * std::cos(2.0 * std::numbers::pi * uniform());
  }

  /// Derives independent seeds for several parts from one user seed.
  static std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
  }

 private:
  std::uint64_t state_;
};

}  // namespace rotord::sim
