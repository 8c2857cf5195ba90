#pragma once
#include <array>
#include <cstdint>

#include "sensors/position_sensor.hpp"
#include "util/time.hpp"

namespace rotord {

/// How a pot reading is filtered (settings *.pot_samples, *.pot_median,
/// *.pot_lowpass_ms).
struct PotFilterConfig {
  static constexpr int kMaxSamples = 32;
  int samples = 8;     ///< ADC conversions per reading, 1..kMaxSamples
  bool median = true;  ///< median of the last three readings
  int lowpass_ms = 0;  ///< first-order low-pass time constant, 0 = off
};

/// One burst of conversions reduced to a value: the median decides, then
/// conversions farther than `spike_counts` from it are dropped (a relay
/// spike, a bad contact) and the rest averaged (white ADC noise falls with
/// the square root of their number).
struct BurstResult {
  bool ok = false;
  float counts = 0.0f;
  SensorFault fault = SensorFault::kNone;
};

/// `samples` is sorted in place. A median within `rail_margin` of 0 or
/// `full_scale` is an open or shorted wiper (kOutOfRange); fewer than half of
/// the conversions near the median is a noise burst (kImplausible).
BurstResult reduce_burst(std::uint16_t* samples, int count, std::uint16_t full_scale,
                         int rail_margin);

/// The filter over successive readings: an optional median of three (a
/// single bad reading never reaches the axis) and an optional low-pass in
/// real time. Fixed size, no heap.
class PotFilter {
 public:
  void configure(const PotFilterConfig& config);
  /// Feeds one burst value taken at `now`; returns the filtered counts.
  float step(float counts, Millis now);
  /// Forgets the history (after a fault, so the old value does not drag).
  void reset() {
    history_count_ = 0;
    have_output_ = false;
  }

 private:
  PotFilterConfig config_;
  std::array<float, 3> history_{};
  int history_count_ = 0;
  int history_head_ = 0;
  bool have_output_ = false;
  float output_ = 0.0f;
  Millis last_ = 0;
};

}  // namespace rotord
