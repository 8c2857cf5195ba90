#include "sensors/ma3_sensor.hpp"

#include "motion/angles.hpp"

namespace rotord {

Ma3Timing ma3_timing(int bits) {
  // Nominal 1025 us and 4097 us; the datasheet's frequency range (877..1072
  // Hz, 220..268 Hz) gives 933..1140 us and 3731..4545 us; 5 % more either
  // way for edge-timing error.
  if (bits == 10) return {1024, 886, 1197};
  return {4096, 3544, 4772};
}

std::optional<int> ma3_decode_code(const hal::PwmPeriod& period, int bits) {
  if (!period.valid) return std::nullopt;
  const std::uint64_t total = std::uint64_t{period.high_us} + period.low_us;
  if (total == 0) return std::nullopt;
  const std::int64_t counts = ma3_timing(bits).counts;
  // The frame: t_on = (code + 1) clocks of a (counts + 1)-clock period, so
  // code = t_on * (counts + 1) / period - 1, rounded to the nearest code
  // (edge-timing jitter is symmetric). The datasheet's truncating
  // t_on * (counts + 2) / period - 1 gives the same code for an exact frame.
  std::int64_t code = (static_cast<std::int64_t>(period.high_us) * (counts + 1) +
                       static_cast<std::int64_t>(total / 2)) /
                          static_cast<std::int64_t>(total) -
                      1;
  if (code < 0) code = 0;
  if (code > counts - 1) code = counts - 1;
  return static_cast<int>(code);
}

void Ma3Sensor::configure(int bits, float zero_deg, bool reverse) {
  if (bits != bits_) have_code_ = have_candidate_ = false;
  bits_ = bits;
  timing_ = ma3_timing(bits);
  zero_deg_ = zero_deg;
  reverse_ = reverse;
}

int Ma3Sensor::circular_distance(int a, int b) const {
  int d = a - b;
  if (d < 0) d = -d;
  return d > timing_.counts / 2 ? timing_.counts - d : d;
}

PositionReading Ma3Sensor::read(Millis /*now*/) {
  PositionReading r;
  const hal::PwmPeriod period = input_.read();
  const auto code = ma3_decode_code(period, bits_);
  if (!code) {
    last_reject_ = Ma3Reject::kNoSignal;
    have_code_ = have_candidate_ = false;  // unplugged: start afresh when it is back
    r.fault = SensorFault::kNoSignal;
    return r;
  }
  r.raw = static_cast<float>(*code);
  const std::uint32_t length_us = period.high_us + period.low_us;
  if (length_us < timing_.min_period_us || length_us > timing_.max_period_us) {
    last_reject_ = Ma3Reject::kBadPeriod;
    r.fault = SensorFault::kImplausible;
    return r;
  }
  if (have_code_ && circular_distance(*code, code_) > confirm_counts()) {
    const bool confirmed =
        have_candidate_ && circular_distance(*code, candidate_) <= confirm_counts();
    if (!confirmed) {
      have_candidate_ = true;
      candidate_ = *code;
      last_reject_ = Ma3Reject::kUnconfirmed;
      r.fault = SensorFault::kImplausible;
      return r;
    }
  }
  have_code_ = true;
  have_candidate_ = false;
  code_ = *code;
  last_reject_ = Ma3Reject::kNone;

  float deg = static_cast<float>(*code) * 360.0f / static_cast<float>(timing_.counts);
  if (reverse_) deg = -deg;
  r.deg = wrap_360(deg - zero_deg_);
  r.ok = true;
  return r;
}

}  // namespace rotord
