#include "sensors/pot_sensor.hpp"

#include <algorithm>
#include <array>

namespace rotord {

void PotSensor::configure(const PotCalibration& cal, const PotFilterConfig& filter) {
  cal_ = cal;
  filter_config_ = filter;
  filter_config_.samples = std::clamp(filter.samples, 1, PotFilterConfig::kMaxSamples);
  filter_.configure(filter_config_);
}

PositionReading PotSensor::read(Millis now) {
  std::array<std::uint16_t, PotFilterConfig::kMaxSamples> samples{};
  const int count = filter_config_.samples;
  for (int n = 0; n < count; ++n) samples[static_cast<std::size_t>(n)] = adc_.read_counts();
  const BurstResult burst =
      reduce_burst(samples.data(), count, adc_.full_scale_counts(), kRailMarginCounts);

  PositionReading r;
  r.raw = burst.counts;
  if (!burst.ok) {
    r.fault = burst.fault;
    filter_.reset();
    return r;
  }
  const float counts = filter_.step(burst.counts, now);
  r.raw = counts;
  r.ok = true;
  r.deg = cal_.to_deg(counts);
  return r;
}

}  // namespace rotord
