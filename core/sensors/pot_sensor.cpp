#include "sensors/pot_sensor.hpp"

#include <algorithm>
#include <array>

namespace rotord {

PositionReading PotSensor::read() {
  std::array<std::uint16_t, kSamples> samples{};
  for (auto& s : samples) s = adc_.read_counts();
  std::sort(samples.begin(), samples.end());
  float sum = 0.0f;
  for (int n = kSamples / 4; n < kSamples - kSamples / 4; ++n) sum += samples[n];
  const float counts = sum / static_cast<float>(kSamples / 2);

  PositionReading r;
  r.raw = counts;
  const float top = static_cast<float>(adc_.full_scale_counts() - kRailMarginCounts);
  if (counts < static_cast<float>(kRailMarginCounts) || counts > top) {
    r.fault = SensorFault::kOutOfRange;
    return r;
  }
  r.ok = true;
  r.deg = cal_.to_deg(counts);
  return r;
}

}  // namespace rotord
