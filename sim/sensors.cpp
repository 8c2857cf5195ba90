#include "sim/sensors.hpp"

#include <algorithm>
#include <cmath>

#include "sim/adc_scale.hpp"

namespace rotord::sim {

// ---- SimPot ----

std::uint16_t SimPot::convert(double volts) const {
  const double code = std::round(adc_counts_exact(volts));
  return static_cast<std::uint16_t>(std::clamp(code, 0.0, double{kAdcFullScaleCounts}));
}

std::uint16_t SimPot::read_counts() {
  if (loss_.active(now_s_)) return 0;
  if (stuck_.active(now_s_)) return stuck_counts_;
  const double sigma_v = noise_burst_.active(now_s_) ? burst_sigma_v_ : config_.sigma_v;
  return convert(volts_at(plant_.theta_deg()) + rng_.normal(sigma_v));
}

std::uint16_t SimPot::full_scale_counts() const {
  return kAdcFullScaleCounts;
}

float SimPot::reference_v() const {
  return static_cast<float>(kAdcVref_v);
}

void SimPot::inject_noise_burst(double sigma_v, double duration_s) {
  burst_sigma_v_ = sigma_v;
  noise_burst_.start(now_s_, duration_s);
}

void SimPot::inject_stuck(double duration_s) {
  stuck_.clear();  // so the frozen value is a live reading, not an older freeze
  stuck_counts_ = read_counts();
  stuck_.start(now_s_, duration_s);
}

void SimPot::clear_faults() {
  loss_.clear();
  noise_burst_.clear();
  stuck_.clear();
}

// ---- SimMa3 ----

void SimMa3::update(double now_s) {
  now_s_ = now_s;
  if (now_s_ + 1e-9 < next_refresh_s_) return;
  sample();
}

void SimMa3::sample() {
  // Even while stuck the refresh schedule keeps running, so sampling resumes
  // on the encoder's own rhythm afterwards.
  next_refresh_s_ = now_s_ + kRefresh_s;
  if (stuck_.active(now_s_)) return;
  const double sigma_deg = noise_burst_.active(now_s_) ? burst_sigma_deg_ : sigma_deg_;
  const double wrapped_deg = std::fmod(plant_.theta_deg() + mount_deg_, 360.0);
  const double deg = wrapped_deg + rng_.normal(sigma_deg);
  const auto raw = static_cast<long long>(std::floor(deg / 360.0 * kCounts));
  code_ = static_cast<int>(((raw % kCounts) + kCounts) % kCounts);  // noise may cross 0/360
}

hal::PwmPeriod SimMa3::read() {
  hal::PwmPeriod period;
  if (loss_.active(now_s_)) return period;  // valid = false, as after an edge timeout
  period.high_us = static_cast<std::uint32_t>(code_ + 1);
  period.low_us = kFrame_us - period.high_us;
  period.valid = true;
  return period;
}

void SimMa3::inject_noise_burst(double sigma_deg, double duration_s) {
  burst_sigma_deg_ = sigma_deg;
  noise_burst_.start(now_s_, duration_s);
}

void SimMa3::clear_faults() {
  loss_.clear();
  noise_burst_.clear();
  stuck_.clear();
}

// ---- SimSwitch ----

bool SimSwitch::active() {
  if (stuck_.active(now_s_)) return stuck_state_;
  const double theta_deg = plant_.theta_deg();
  return sense_ == Sense::kAtOrAbove ? theta_deg >= threshold_deg_ : theta_deg <= threshold_deg_;
}

bool SimMag::write(std::uint8_t address, const std::uint8_t* /*data*/, std::size_t length) {
  return address == kAddress && length >= 1;  // control writes: always continuous mode here
}

bool SimMag::write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                        std::uint8_t* rdata, std::size_t rlength) {
  if (address != kAddress || wlength != 1) return false;
  std::uint8_t regs[14] = {};
  const double rad = (plant_.theta_deg() + mount_deg_) * (3.14159265358979 / 180.0);
  const auto put = [&](int reg, double value) {
    const auto v = static_cast<std::int16_t>(std::lround(value + rng_.normal(sigma_counts_)));
    regs[reg] = static_cast<std::uint8_t>(static_cast<std::uint16_t>(v) & 0xFF);
    regs[reg + 1] = static_cast<std::uint8_t>(static_cast<std::uint16_t>(v) >> 8);
  };
  put(0x00, kOffsetX + kGainX * std::cos(rad));
  put(0x02, kOffsetY + kGainY * std::sin(rad));
  put(0x04, kZ);
  regs[0x06] = 0x01;  // data ready, no overflow
  regs[0x0D] = 0xFF;  // chip id
  for (std::size_t n = 0; n < rlength; ++n) {
    const std::size_t reg = wdata[0] + n;
    rdata[n] = reg < sizeof regs ? regs[reg] : 0;
  }
  return true;
}

}  // namespace rotord::sim
