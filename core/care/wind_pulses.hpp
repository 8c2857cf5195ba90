#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "util/time.hpp"

namespace rotord::care {

/// An anemometer's wind speed from its pulse count: the pulses of the last
/// 2 s over the time they took, divided by wind.pulses_per_mps. Shorter than
/// the WMO's 3 s gust average, as wind.hold_s does the smoothing: a storm's
/// step is read within 1.5 s, so the stow begins within 2 s of the wind
/// holding the threshold. A sample every 250 ms in a ring: no heap, a few
/// operations a tick (M0+).
class WindPulseMeter {
 public:
  static constexpr Millis kSampleMs = 250;
  static constexpr std::size_t kSamples = 9;  ///< 8 intervals: 2 s

  /// `count`: the counter now. A speed (m/s) every kSampleMs once two
  /// samples are in, else nothing.
  std::optional<float> sample(std::uint32_t count, Millis now, float pulses_per_mps);
  void reset() { filled_ = 0; }

 private:
  struct Sample {
    Millis at_ms = 0;
    std::uint32_t count = 0;
  };
  std::array<Sample, kSamples> ring_{};
  std::size_t next_ = 0;
  std::size_t filled_ = 0;
};

}  // namespace rotord::care
