#include "sensors/pot_filter.hpp"

#include <algorithm>

namespace rotord {

BurstResult reduce_burst(std::uint16_t* samples, int count, std::uint16_t full_scale,
                         int rail_margin) {
  BurstResult r;
  if (count <= 0) {
    r.fault = SensorFault::kNoSignal;
    return r;
  }
  std::sort(samples, samples + count);
  const int mid = count / 2;
  const float median = count % 2 != 0 ? samples[mid] : 0.5f * (samples[mid - 1] + samples[mid]);
  if (median < static_cast<float>(rail_margin) ||
      median > static_cast<float>(full_scale - rail_margin)) {
    r.fault = SensorFault::kOutOfRange;
    r.counts = median;
    return r;
  }
  // 1/32 of full scale (128 counts on the RP2040): 20 times the ADC's RMS
  // noise, and 14 deg on a G-5500 azimuth pot, so a turning rotator never
  // moves a conversion this far within one burst (a few hundred us).
  const float spike = std::max(16.0f, static_cast<float>(full_scale) / 32.0f);
  float sum = 0.0f;
  int kept = 0;
  for (int n = 0; n < count; ++n) {
    const float s = samples[n];
    if (s < median - spike || s > median + spike) continue;
    sum += s;
    ++kept;
  }
  if (2 * kept < count) {
    r.fault = SensorFault::kImplausible;
    r.counts = median;
    return r;
  }
  r.ok = true;
  r.counts = sum / static_cast<float>(kept);
  return r;
}

void PotFilter::configure(const PotFilterConfig& config) {
  if (config.median != config_.median) reset();
  config_ = config;
}

float PotFilter::step(float counts, Millis now) {
  float value = counts;
  history_[static_cast<std::size_t>(history_head_)] = counts;
  history_head_ = (history_head_ + 1) % 3;
  if (history_count_ < 3) ++history_count_;
  if (config_.median && history_count_ == 3) {
    const float a = history_[0], b = history_[1], c = history_[2];
    value = std::max(std::min(a, b), std::min(std::max(a, b), c));
  }
  if (config_.lowpass_ms <= 0 || !have_output_) {
    output_ = value;
  } else if (now > last_) {
    // Exact discretisation would need expf; dt / (tau + dt) is within a few
    // percent of it for dt << tau and stays stable for any dt.
    const float dt = static_cast<float>(now - last_);
    output_ += (value - output_) * dt / (static_cast<float>(config_.lowpass_ms) + dt);
  }
  have_output_ = true;
  last_ = now;
  return output_;
}

}  // namespace rotord
