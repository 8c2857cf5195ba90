#include "care/wind_pulses.hpp"

namespace rotord::care {

std::optional<float> WindPulseMeter::sample(std::uint32_t count, Millis now, float pulses_per_mps) {
  if (filled_ > 0) {
    const Sample& last = ring_[(next_ + kSamples - 1) % kSamples];
    if (now - last.at_ms < kSampleMs) return std::nullopt;
  }
  ring_[next_] = {now, count};
  next_ = (next_ + 1) % kSamples;
  if (filled_ < kSamples) ++filled_;
  if (filled_ < 2 || pulses_per_mps <= 0.0f) return std::nullopt;
  const Sample& oldest = ring_[(next_ + kSamples - filled_) % kSamples];
  const Millis span_ms = now - oldest.at_ms;
  if (span_ms <= 0) return std::nullopt;
  // Unsigned difference: right across the counter's wrap.
  const std::uint32_t pulses = count - oldest.count;
  const float hz = static_cast<float>(pulses) * 1000.0f / static_cast<float>(span_ms);
  return hz / pulses_per_mps;
}

}  // namespace rotord::care
